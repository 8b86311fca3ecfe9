//! The fixed-size NPY v1.0 header.

/// Bytes before the data: magic (6) + version (2) + header length (2) + header text.
/// 128 keeps the data 64-byte aligned, as numpy recommends, and leaves room for a shape
/// of two 20-digit numbers, so the header can be rewritten in place as rows are added.
pub(crate) const HEADER_BYTES: usize = 128;

/// The full header for an `<f8`, C-order array of the given shape.
pub(crate) fn header(shape: &[u64]) -> [u8; HEADER_BYTES] {
    let dims = match shape {
        [n] => format!("({n},)"),
        _ => {
            let parts: Vec<String> = shape.iter().map(u64::to_string).collect();
            format!("({})", parts.join(", "))
        }
    };
    let dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {dims}, }}");
    let mut out = [b' '; HEADER_BYTES];
    out[..6].copy_from_slice(b"\x93NUMPY");
    out[6] = 1;
    out[7] = 0;
    // HEADER_BYTES - 10 = 118 fits in the u16 length field.
    let text_len = (HEADER_BYTES - 10) as u16;
    out[8..10].copy_from_slice(&text_len.to_le_bytes());
    // Two u64 dimensions take at most 40 digits; the dict text is < 100 bytes, never truncated.
    let n = dict.len().min(HEADER_BYTES - 11);
    out[10..10 + n].copy_from_slice(&dict.as_bytes()[..n]);
    out[HEADER_BYTES - 1] = b'\n';
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_layout() {
        let h = header(&[u64::MAX, u64::MAX]);
        let text = std::str::from_utf8(&h[10..]).unwrap();
        assert!(text.starts_with(
            "{'descr': '<f8', 'fortran_order': False, 'shape': (18446744073709551615, 18446744073709551615), }"
        ));
        assert!(text.ends_with(" \n"));
        assert_eq!(u16::from_le_bytes([h[8], h[9]]), 118);
        let h = header(&[3]);
        assert!(
            std::str::from_utf8(&h[10..])
                .unwrap()
                .contains("'shape': (3,), }")
        );
    }
}
