//! Leaf helpers on fixed-point codes: masks, bit lengths, sized Verilog literals, exact
//! decimals of dyadic fractions, and the small counter-based generator the stimuli use.
//! Imports nothing from the crate.

/// The low `bits` bits set (all 128 when `bits >= 128`).
pub(crate) fn mask(bits: u32) -> u128 {
    if bits >= 128 {
        u128::MAX
    } else {
        (1u128 << bits) - 1
    }
}

/// An unsigned machine word a golden model computes in: `u64` when every value of its datapath
/// fits (about three times faster on the exhaustive sweep), `u128` otherwise. The arithmetic is
/// written once, generic over the word, so both run the same steps.
pub(crate) trait Word:
    Copy
    + Eq
    + Ord
    + From<u32>
    + Into<u128>
    + std::ops::Shl<u32, Output = Self>
    + std::ops::Shr<u32, Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::BitAnd<Output = Self>
{
    fn wrapping_sub(self, other: Self) -> Self;
    /// The low `bits` bits set (all when `bits >= BITS`).
    fn mask(bits: u32) -> Self;
    /// The low bits of a wider value (a code known to fit).
    fn low(v: u128) -> Self;
}

macro_rules! word {
    ($t:ty) => {
        impl Word for $t {
            fn wrapping_sub(self, other: Self) -> Self {
                <$t>::wrapping_sub(self, other)
            }
            fn mask(bits: u32) -> Self {
                if bits >= <$t>::BITS {
                    <$t>::MAX
                } else {
                    ((1 as $t) << bits) - 1
                }
            }
            fn low(v: u128) -> Self {
                v as $t
            }
        }
    };
}
word!(u64);
word!(u128);

/// Number of bits needed to hold `v` (0 for 0).
pub(crate) fn bit_length(v: u128) -> u32 {
    128 - v.leading_zeros()
}

/// A sized Verilog literal, `W'hX`.
pub(crate) fn lit(width: u32, value: u128) -> String {
    format!("{width}'h{value:x}")
}

/// `code / 2^F` written exactly in decimal (a dyadic fraction always has a finite expansion).
pub fn exact_decimal(code: u64, frac_bits: u32) -> String {
    let int = code >> frac_bits;
    let mut rem = (code & ((1u64 << frac_bits) - 1)) as u128;
    let mut s = format!("{int}.");
    if rem == 0 {
        s.push('0');
    }
    while rem != 0 {
        rem *= 10;
        s.push(char::from(b'0' + (rem >> frac_bits) as u8));
        rem &= (1u128 << frac_bits) - 1;
    }
    s
}

/// splitmix64: a small counter-based generator, so vectors are reproducible from the seed.
pub fn splitmix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// The first `bytes` bytes of the SHA-256 of `data`, as lowercase hex (32: the whole digest):
/// the manifest's file hashes, the fingerprint, cache keys and staging tags.
pub fn sha256_hex(data: &[u8], bytes: usize) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(data)
        .iter()
        .take(bytes)
        .map(|b| format!("{b:02x}"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_decimal_is_exact() {
        assert_eq!(exact_decimal(1, 1), "0.5");
        assert_eq!(exact_decimal(3, 2), "0.75");
        assert_eq!(exact_decimal(1 << 15, 15), "1.0");
        assert_eq!(exact_decimal(1, 15), "0.000030517578125");
    }

    #[test]
    fn masks_and_lengths() {
        assert_eq!(mask(0), 0);
        assert_eq!(mask(5), 31);
        assert_eq!(mask(128), u128::MAX);
        assert_eq!(bit_length(0), 0);
        assert_eq!(bit_length(1 << 20), 21);
        assert_eq!(lit(6, 10), "6'ha");
    }
}
