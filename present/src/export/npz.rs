//! NumPy `.npz` writing and reading through `ndarray-npy` (an uncompressed zip of `.npy`
//! arrays), so exported data opens with `numpy.load` and no Python is needed to produce it.
//! Reading a truncated or corrupt file is an error, never a panic.

use ndarray::{ArrayD, IxDyn};
use ndarray_npy::{NpzReader, NpzWriter, ReadNpzError};
use std::io::{Cursor, Seek, Write};

/// Element data of one array.
#[derive(Debug, Clone, PartialEq)]
pub enum NpyData {
    /// `<f4`.
    F32(Vec<f32>),
    /// `<f8`.
    F64(Vec<f64>),
    /// `<i8`.
    I64(Vec<i64>),
    /// `|u1` (booleans as 0/1).
    U8(Vec<u8>),
}

impl NpyData {
    fn len(&self) -> usize {
        match self {
            NpyData::F32(v) => v.len(),
            NpyData::F64(v) => v.len(),
            NpyData::I64(v) => v.len(),
            NpyData::U8(v) => v.len(),
        }
    }
}

/// One named array.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    /// Name (the key in `numpy.load(...)`).
    pub name: String,
    /// Shape (row-major).
    pub shape: Vec<usize>,
    /// Elements (`product(shape)` of them).
    pub data: NpyData,
}

fn nd<T: Clone>(name: &str, shape: &[usize], v: &[T]) -> Result<ArrayD<T>, String> {
    ArrayD::from_shape_vec(IxDyn(shape), v.to_vec())
        .map_err(|e| format!("array `{name}`: shape {shape:?} does not fit the data ({e})"))
}

/// Writes `arrays` as an `.npz` archive into `w` (row-major, little-endian, uncompressed).
/// A shape that does not match its data is an error.
pub fn write_npz<W: Write + Seek>(w: W, arrays: &[NpyArray]) -> Result<W, String> {
    let mut npz = NpzWriter::new(w);
    for a in arrays {
        if a.shape.iter().product::<usize>() != a.data.len() {
            return Err(format!(
                "array `{}`: shape {:?} holds {} elements, data has {}",
                a.name,
                a.shape,
                a.shape.iter().product::<usize>(),
                a.data.len()
            ));
        }
        let e = |e: ndarray_npy::WriteNpzError| format!("array `{}`: {e}", a.name);
        match &a.data {
            NpyData::F32(v) => npz.add_array(a.name.as_str(), &nd(&a.name, &a.shape, v)?),
            NpyData::F64(v) => npz.add_array(a.name.as_str(), &nd(&a.name, &a.shape, v)?),
            NpyData::I64(v) => npz.add_array(a.name.as_str(), &nd(&a.name, &a.shape, v)?),
            NpyData::U8(v) => npz.add_array(a.name.as_str(), &nd(&a.name, &a.shape, v)?),
        }
        .map_err(e)?;
    }
    npz.finish()
        .map_err(|e| format!("finishing the npz archive: {e}"))
}

/// The `.npz` archive of `arrays` as bytes.
pub fn npz_bytes(arrays: &[NpyArray]) -> Result<Vec<u8>, String> {
    Ok(write_npz(Cursor::new(Vec::new()), arrays)?.into_inner())
}

/// Reads an `.npz` archive of `f4`/`f8`/`i8`/`u1` arrays: `(name, dtype, shape, array)` per
/// entry, in archive order. Truncated, corrupt or other-typed data is an error (never a
/// panic).
pub fn read_npz(bytes: &[u8]) -> Result<Vec<NpyArray>, String> {
    let mut npz =
        NpzReader::new(Cursor::new(bytes)).map_err(|e| format!("not an npz archive: {e}"))?;
    let names = npz.names().map_err(|e| format!("npz archive: {e}"))?;
    let mut out = Vec::with_capacity(names.len());
    for name in names {
        let err = |e: ReadNpzError| format!("array `{name}`: {e}");
        let (shape, data) = if let Ok(a) = npz.by_name::<_, IxDyn>(&name).map(|a: ArrayD<f32>| a) {
            (
                a.shape().to_vec(),
                NpyData::F32(a.iter().copied().collect()),
            )
        } else if let Ok(a) = npz.by_name::<_, IxDyn>(&name).map(|a: ArrayD<f64>| a) {
            (
                a.shape().to_vec(),
                NpyData::F64(a.iter().copied().collect()),
            )
        } else if let Ok(a) = npz.by_name::<_, IxDyn>(&name).map(|a: ArrayD<i64>| a) {
            (
                a.shape().to_vec(),
                NpyData::I64(a.iter().copied().collect()),
            )
        } else {
            let a: ArrayD<u8> = npz.by_name(&name).map_err(err)?;
            (a.shape().to_vec(), NpyData::U8(a.iter().copied().collect()))
        };
        out.push(NpyArray { name, shape, data });
    }
    Ok(out)
}
