//! Reading the weights of a checkpoint's `model.bpk` without burn.
//!
//! A burnpack file (burn 0.22's format) is a 10-byte header — magic `0x4255524E` ("BURN",
//! little-endian u32), format version (u16, 1), metadata size (u32) — then CBOR metadata
//! `{tensors: {name: {dtype, shape, data_offsets: [start, end], param_id}}, …}`, then the
//! tensor data section, which starts at the next 256-byte boundary after the metadata; each
//! tensor's bytes are `data_offsets` relative to that section, little-endian. fairgrasp's
//! networks are f32 throughout; other dtypes are refused.

use std::collections::BTreeMap;

use serde::Deserialize;

/// "BURN" as a little-endian u32.
const MAGIC: u32 = 0x4255_524E;
/// The format version this reader knows.
const VERSION: u16 = 1;
const HEADER: usize = 10;
const ALIGNMENT: usize = 256;
/// The largest metadata blob accepted \[bytes\] (a fairgrasp network's is about 1 KiB).
const MAX_METADATA: usize = 1 << 20;

/// Why a burnpack file cannot be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BurnpackError {
    #[error("not a burnpack file ({0})")]
    NotBurnpack(String),
    #[error("burnpack metadata: {0}")]
    Metadata(String),
    #[error("tensor `{name}`: {reason}")]
    Tensor { name: String, reason: String },
}

#[derive(Deserialize)]
struct Descriptor {
    dtype: String,
    shape: Vec<u64>,
    data_offsets: (u64, u64),
}

#[derive(Deserialize)]
struct Metadata {
    tensors: BTreeMap<String, Descriptor>,
}

/// One f32 tensor: its shape and values (row-major).
#[derive(Clone, Debug, PartialEq)]
pub struct Tensor {
    pub shape: Vec<usize>,
    pub values: Vec<f32>,
}

/// Every tensor of a burnpack file, by name (burn's module paths, e.g. `actor.0.weight`).
pub fn read_tensors(bytes: &[u8]) -> Result<BTreeMap<String, Tensor>, BurnpackError> {
    let not = |why: &str| BurnpackError::NotBurnpack(why.to_string());
    if bytes.len() < HEADER {
        return Err(not("shorter than its 10-byte header"));
    }
    let magic = u32::from_le_bytes(bytes[0..4].try_into().expect("4 bytes"));
    let version = u16::from_le_bytes(bytes[4..6].try_into().expect("2 bytes"));
    let size = u32::from_le_bytes(bytes[6..10].try_into().expect("4 bytes")) as usize;
    if magic != MAGIC {
        return Err(not("wrong magic number"));
    }
    if version != VERSION {
        return Err(not(&format!(
            "format version {version}, this reader knows {VERSION}"
        )));
    }
    if size > MAX_METADATA || HEADER + size > bytes.len() {
        return Err(not(&format!(
            "metadata of {size} bytes does not fit the {}-byte file",
            bytes.len()
        )));
    }
    let metadata: Metadata = ciborium::from_reader(&bytes[HEADER..HEADER + size])
        .map_err(|e| BurnpackError::Metadata(e.to_string()))?;
    let data_start = (HEADER + size).div_ceil(ALIGNMENT) * ALIGNMENT;
    let data = bytes.get(data_start..).unwrap_or_default();
    let mut out = BTreeMap::new();
    for (name, d) in metadata.tensors {
        let fail = |reason: String| BurnpackError::Tensor {
            name: name.clone(),
            reason,
        };
        if d.dtype != "F32" {
            return Err(fail(format!("dtype {} (only F32 is read)", d.dtype)));
        }
        let (start, end) = (d.data_offsets.0 as usize, d.data_offsets.1 as usize);
        let elements = d
            .shape
            .iter()
            .try_fold(1usize, |n, &s| n.checked_mul(s as usize))
            .ok_or_else(|| fail(format!("shape {:?} overflows", d.shape)))?;
        let raw = data
            .get(start..end)
            .filter(|r| Some(r.len()) == elements.checked_mul(4))
            .ok_or_else(|| {
                fail(format!(
                    "bytes {start}..{end} of a {}-byte data section do not hold {elements} f32",
                    data.len()
                ))
            })?;
        let values = raw
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
            .collect();
        let shape = d.shape.iter().map(|&s| s as usize).collect();
        out.insert(name, Tensor { shape, values });
    }
    Ok(out)
}
