//! NumPy `.npz` writing and reading (uncompressed zip of `.npy` v1.0 arrays), so exported
//! data opens with `numpy.load` and no Python is needed to produce it.
//!
//! `.npy` v1.0: magic `\x93NUMPY`, version 1.0, a little-endian `u16` header length, an
//! ASCII dict `{'descr': '<f4', 'fortran_order': False, 'shape': (…), }` padded with spaces
//! and a newline so the data starts at a multiple of 64 bytes; data row-major little-endian.

use std::io::Write;

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
    fn descr(&self) -> &'static str {
        match self {
            NpyData::F32(_) => "<f4",
            NpyData::F64(_) => "<f8",
            NpyData::I64(_) => "<i8",
            NpyData::U8(_) => "|u1",
        }
    }

    fn len(&self) -> usize {
        match self {
            NpyData::F32(v) => v.len(),
            NpyData::F64(v) => v.len(),
            NpyData::I64(v) => v.len(),
            NpyData::U8(v) => v.len(),
        }
    }

    fn bytes(&self) -> Vec<u8> {
        match self {
            NpyData::F32(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            NpyData::F64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            NpyData::I64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            NpyData::U8(v) => v.clone(),
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

/// Serialises one array as `.npy` v1.0. Panics never; a shape/data mismatch is an error.
pub fn npy_bytes(a: &NpyArray) -> Result<Vec<u8>, String> {
    let n: usize = a.shape.iter().product();
    if n != a.data.len() {
        return Err(format!(
            "array {}: shape {:?} needs {n} elements, has {}",
            a.name,
            a.shape,
            a.data.len()
        ));
    }
    let shape = match a.shape.len() {
        1 => format!("({},)", a.shape[0]),
        _ => format!(
            "({})",
            a.shape
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let mut header = format!(
        "{{'descr': '{}', 'fortran_order': False, 'shape': {shape}, }}",
        a.data.descr()
    );
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - total % 64) % 64));
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend(a.data.bytes());
    Ok(out)
}

fn crc32(data: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Writes arrays as an uncompressed `.npz` (zip, method "stored") into `w`.
pub fn write_npz<W: Write>(w: &mut W, arrays: &[NpyArray]) -> Result<(), String> {
    let mut central = Vec::new();
    let mut offset = 0u32;
    let io = |e: std::io::Error| e.to_string();
    for a in arrays {
        let data = npy_bytes(a)?;
        let name = format!("{}.npy", a.name);
        let crc = crc32(&data);
        let size = u32::try_from(data.len()).map_err(|_| format!("array {} over 4 GiB", a.name))?;
        let mut local = Vec::new();
        local.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        local.extend_from_slice(&20u16.to_le_bytes()); // version needed
        local.extend_from_slice(&0u16.to_le_bytes()); // flags
        local.extend_from_slice(&0u16.to_le_bytes()); // stored
        local.extend_from_slice(&0u16.to_le_bytes()); // time
        local.extend_from_slice(&0x21u16.to_le_bytes()); // date 1980-01-01
        local.extend_from_slice(&crc.to_le_bytes());
        local.extend_from_slice(&size.to_le_bytes());
        local.extend_from_slice(&size.to_le_bytes());
        local.extend_from_slice(&(name.len() as u16).to_le_bytes());
        local.extend_from_slice(&0u16.to_le_bytes());
        local.extend_from_slice(name.as_bytes());
        w.write_all(&local).map_err(io)?;
        w.write_all(&data).map_err(io)?;
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&20u16.to_le_bytes()); // made by
        central.extend_from_slice(&local[4..30]);
        central.extend_from_slice(&0u16.to_le_bytes()); // comment
        central.extend_from_slice(&0u16.to_le_bytes()); // disk
        central.extend_from_slice(&0u16.to_le_bytes()); // internal attrs
        central.extend_from_slice(&0u32.to_le_bytes()); // external attrs
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
        offset = offset
            .checked_add((local.len() + data.len()) as u32)
            .ok_or("npz over 4 GiB")?;
    }
    let n = arrays.len() as u16;
    let mut end = Vec::new();
    end.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    end.extend_from_slice(&[0, 0, 0, 0]);
    end.extend_from_slice(&n.to_le_bytes());
    end.extend_from_slice(&n.to_le_bytes());
    end.extend_from_slice(&(central.len() as u32).to_le_bytes());
    end.extend_from_slice(&offset.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes());
    w.write_all(&central).map_err(io)?;
    w.write_all(&end).map_err(io)?;
    Ok(())
}

/// Reads back an `.npz` written by [`write_npz`] (stored entries; checks CRCs):
/// `(name, descr, shape, raw little-endian data)` per array.
#[allow(clippy::type_complexity)]
pub fn read_npz(bytes: &[u8]) -> Result<Vec<(String, String, Vec<usize>, Vec<u8>)>, String> {
    let mut out = Vec::new();
    let mut p = 0usize;
    let u16_at = |p: usize| u16::from_le_bytes([bytes[p], bytes[p + 1]]) as usize;
    let u32_at =
        |p: usize| u32::from_le_bytes([bytes[p], bytes[p + 1], bytes[p + 2], bytes[p + 3]]);
    while p + 30 <= bytes.len() && u32_at(p) == 0x0403_4b50 {
        let crc = u32_at(p + 14);
        let size = u32_at(p + 18) as usize;
        let name_len = u16_at(p + 26);
        let extra = u16_at(p + 28);
        let name = String::from_utf8_lossy(&bytes[p + 30..p + 30 + name_len]).to_string();
        let start = p + 30 + name_len + extra;
        let data = bytes.get(start..start + size).ok_or("truncated entry")?;
        if crc32(data) != crc {
            return Err(format!("{name}: CRC mismatch"));
        }
        if !data.starts_with(b"\x93NUMPY") {
            return Err(format!("{name}: not an .npy"));
        }
        let hlen = u16::from_le_bytes([data[8], data[9]]) as usize;
        let header = String::from_utf8_lossy(&data[10..10 + hlen]).to_string();
        let descr = header
            .split("'descr': '")
            .nth(1)
            .and_then(|s| s.split('\'').next())
            .unwrap_or("")
            .to_string();
        let shape: Vec<usize> = header
            .split("'shape': (")
            .nth(1)
            .and_then(|s| s.split(')').next())
            .unwrap_or("")
            .split(',')
            .filter_map(|d| d.trim().parse().ok())
            .collect();
        out.push((
            name.trim_end_matches(".npy").to_string(),
            descr,
            shape,
            data[10 + hlen..].to_vec(),
        ));
        p = start + size;
    }
    Ok(out)
}
