//! Reading JSON that the lab wrote with undefined statistics as `null` (serde_json writes a
//! NaN `f64` as `null`) back into the same types: a `null` where a plain `f64`/`f32` is
//! expected reads as NaN, everywhere in the structure (fields, vectors, tuples, arrays),
//! while `null` for an `Option` still reads as `None`. Everything else is read as
//! serde_json reads it.
//!
//! Used for files written before (or without) per-field `nan_if_null` attributes, e.g.
//! `metrics.json` of compact study results.

use serde::de::{
    self, DeserializeOwned, DeserializeSeed, Deserializer, EnumAccess, IntoDeserializer, MapAccess,
    SeqAccess, VariantAccess, Visitor,
};
use serde_json::{Error, Value};

/// Deserialises `T` from JSON text, reading `null` as NaN where a float is expected.
pub fn from_str_nan<T: DeserializeOwned>(text: &str) -> Result<T, Error> {
    let v: Value = serde_json::from_str(text)?;
    T::deserialize(NanTolerant(&v))
}

/// A JSON value as a deserialiser that reads `null` floats as NaN.
#[derive(Clone, Copy)]
struct NanTolerant<'a>(&'a Value);

struct Seq<'a>(std::slice::Iter<'a, Value>);

impl<'de> SeqAccess<'de> for Seq<'_> {
    type Error = Error;
    fn next_element_seed<S: DeserializeSeed<'de>>(
        &mut self,
        seed: S,
    ) -> Result<Option<S::Value>, Error> {
        self.0
            .next()
            .map(|v| seed.deserialize(NanTolerant(v)))
            .transpose()
    }
    fn size_hint(&self) -> Option<usize> {
        Some(self.0.len())
    }
}

struct Map<'a> {
    it: serde_json::map::Iter<'a>,
    value: Option<&'a Value>,
}

impl<'de> MapAccess<'de> for Map<'_> {
    type Error = Error;
    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        match self.it.next() {
            Some((k, v)) => {
                self.value = Some(v);
                seed.deserialize(k.as_str().into_deserializer()).map(Some)
            }
            None => Ok(None),
        }
    }
    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, Error> {
        let v = self
            .value
            .take()
            .ok_or_else(|| de::Error::custom("value requested before its key"))?;
        seed.deserialize(NanTolerant(v))
    }
}

/// An externally tagged enum variant with content (`{"Variant": content}`).
struct Enum<'a> {
    variant: &'a str,
    content: &'a Value,
}

impl<'de, 'a> EnumAccess<'de> for Enum<'a> {
    type Error = Error;
    type Variant = NanTolerant<'a>;
    fn variant_seed<V: DeserializeSeed<'de>>(
        self,
        seed: V,
    ) -> Result<(V::Value, Self::Variant), Error> {
        let v = seed.deserialize(self.variant.into_deserializer())?;
        Ok((v, NanTolerant(self.content)))
    }
}

impl<'de> VariantAccess<'de> for NanTolerant<'_> {
    type Error = Error;
    fn unit_variant(self) -> Result<(), Error> {
        match self.0 {
            Value::Null => Ok(()),
            other => Err(de::Error::custom(format!(
                "expected a unit variant, found {other}"
            ))),
        }
    }
    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, Error> {
        seed.deserialize(self)
    }
    fn tuple_variant<V: Visitor<'de>>(self, _len: usize, visitor: V) -> Result<V::Value, Error> {
        self.deserialize_any(visitor)
    }
    fn struct_variant<V: Visitor<'de>>(
        self,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        self.deserialize_any(visitor)
    }
}

impl<'de> Deserializer<'de> for NanTolerant<'_> {
    type Error = Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Null => visitor.visit_unit(),
            Value::Bool(b) => visitor.visit_bool(*b),
            Value::Number(n) => {
                if let Some(u) = n.as_u64() {
                    visitor.visit_u64(u)
                } else if let Some(i) = n.as_i64() {
                    visitor.visit_i64(i)
                } else {
                    visitor.visit_f64(n.as_f64().unwrap_or(f64::NAN))
                }
            }
            Value::String(s) => visitor.visit_str(s),
            Value::Array(a) => visitor.visit_seq(Seq(a.iter())),
            Value::Object(m) => visitor.visit_map(Map {
                it: m.iter(),
                value: None,
            }),
        }
    }

    fn deserialize_f64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Null => visitor.visit_f64(f64::NAN),
            _ => self.deserialize_any(visitor),
        }
    }

    fn deserialize_f32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Null => visitor.visit_f32(f32::NAN),
            _ => self.deserialize_any(visitor),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        match self.0 {
            Value::String(s) => visitor.visit_enum(s.as_str().into_deserializer()),
            Value::Object(m) if m.len() == 1 => {
                let (variant, content) = m.iter().next().expect("one entry");
                visitor.visit_enum(Enum { variant, content })
            }
            other => Err(de::Error::custom(format!(
                "expected an enum (a string or an object with one key), found {other}"
            ))),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 char str string bytes byte_buf
        unit unit_struct seq tuple tuple_struct map struct identifier ignored_any
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize, PartialEq)]
    enum Kind {
        Fi,
        Pair(u32, f64),
    }

    #[derive(Debug, Deserialize)]
    struct Sample {
        x: f64,
        maybe: Option<f64>,
        v: Vec<f64>,
        t: (u32, f64),
        a: [f32; 2],
        k: Kind,
        p: Kind,
        nested: Vec<Option<f64>>,
    }

    #[test]
    fn null_floats_read_as_nan_and_null_options_as_none() {
        let s: Sample = from_str_nan(
            r#"{"x": null, "maybe": null, "v": [1.5, null], "t": [3, null], "a": [null, 2],
                "k": "Fi", "p": {"Pair": [4, null]}, "nested": [null, 2.0]}"#,
        )
        .unwrap();
        assert!(s.x.is_nan() && s.maybe.is_none());
        assert_eq!(s.v[0], 1.5);
        assert!(s.v[1].is_nan() && s.t.1.is_nan() && s.a[0].is_nan());
        assert_eq!((s.t.0, s.a[1]), (3, 2.0));
        assert_eq!(s.k, Kind::Fi);
        assert!(matches!(s.p, Kind::Pair(4, y) if y.is_nan()));
        assert_eq!(s.nested[0], None);
        assert_eq!(s.nested[1], Some(2.0));
    }

    #[test]
    fn other_type_errors_are_still_errors() {
        let e = from_str_nan::<Sample>(r#"{"x": "a"}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("invalid type"), "{e}");
        let e = from_str_nan::<Vec<u32>>("[null]").unwrap_err().to_string();
        assert!(e.contains("invalid type"), "{e}");
    }
}
