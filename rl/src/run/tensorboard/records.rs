//! The TFRecord framing of an event file: each record is its length (u64, little endian), the
//! masked CRC-32C of those 8 bytes, the data, and the masked CRC-32C of the data.

use std::io::Write;

/// TensorFlow's CRC mask: rotate right by 15 bits, add a constant.
fn masked_crc(bytes: &[u8]) -> u32 {
    let crc = crc32c::crc32c(bytes);
    crc.rotate_right(15).wrapping_add(0xa282_ead8)
}

/// Writes one record holding `data`.
pub fn write_record(out: &mut impl Write, data: &[u8]) -> std::io::Result<()> {
    let length = (data.len() as u64).to_le_bytes();
    out.write_all(&length)?;
    out.write_all(&masked_crc(&length).to_le_bytes())?;
    out.write_all(data)?;
    out.write_all(&masked_crc(data).to_le_bytes())
}

/// The records of a file's bytes, in order, up to the first one that is cut off or whose
/// checksums do not match (a write torn by a kill: the rest is not trusted).
pub fn read_records(bytes: &[u8]) -> Vec<&[u8]> {
    let mut out = Vec::new();
    let mut rest = bytes;
    while rest.len() >= 12 {
        let (head, tail) = rest.split_at(12);
        let length = u64::from_le_bytes(head[..8].try_into().expect("8 bytes"));
        let crc = u32::from_le_bytes(head[8..12].try_into().expect("4 bytes"));
        let Ok(n) = usize::try_from(length) else {
            break;
        };
        if crc != masked_crc(&head[..8]) || tail.len() < n.saturating_add(4) {
            break;
        }
        let (data, tail) = tail.split_at(n);
        let data_crc = u32::from_le_bytes(tail[..4].try_into().expect("4 bytes"));
        if data_crc != masked_crc(data) {
            break;
        }
        out.push(data);
        rest = &tail[4..];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_read_back_and_a_torn_tail_is_dropped() {
        let mut file = Vec::new();
        write_record(&mut file, b"first").unwrap();
        write_record(&mut file, b"").unwrap();
        write_record(&mut file, b"third record").unwrap();
        assert_eq!(
            read_records(&file),
            vec![&b"first"[..], b"", b"third record"]
        );
        // Cut inside the last record, or flip one bit of its data: two records remain.
        assert_eq!(read_records(&file[..file.len() - 3]).len(), 2);
        let mut flipped = file.clone();
        let n = flipped.len();
        flipped[n - 6] ^= 1;
        assert_eq!(read_records(&flipped).len(), 2);
    }

    #[test]
    fn the_crc_is_crc32c_masked_as_tensorflow_masks_it() {
        // CRC-32C of "123456789" is 0xE3069283 (the standard check value); TensorFlow's mask
        // ((crc >> 15) | (crc << 17)) + 0xa282ead8, worked out by hand: 0xC78AB0E5.
        assert_eq!(crc32c::crc32c(b"123456789"), 0xE306_9283);
        assert_eq!(masked_crc(b"123456789"), 0xC78A_B0E5);
    }
}
