//! The decimal parameters: `--k` and `--clock-mhz` as text, parsed exactly with `fixed`.

use crate::error::Error;

/// Parses a plain decimal (digits and one optional point) to the nearest multiple of
/// `2^-frac_bits` with the `fixed` crate, which converts decimal text with a single correct
/// rounding (to nearest, ties to even) and no binary floating point in between.
/// Returns the integer code `round(x · 2^frac_bits)`. `frac_bits` must be in 1..=24.
pub fn parse_decimal(text: &str, frac_bits: u32) -> Result<u64, Error> {
    let err = |message: String| Error::Config {
        parameter: "decimal",
        message,
    };
    use fixed::types::extra::U120;
    use fixed::FixedU128;
    let trimmed = text.trim();
    let plain = |t: &str| !t.is_empty() && t.chars().all(|c| c.is_ascii_digit() || c == '.');
    if let Some(rest) = trimmed.strip_prefix('-') {
        if plain(rest) {
            return Err(err(format!("{text:?} is negative, out of range")));
        }
    }
    if !plain(trimmed) {
        return Err(err(format!("{text:?} is not a plain decimal number")));
    }
    assert!(
        (1..=24).contains(&frac_bits),
        "parse_decimal: frac_bits {frac_bits} outside 1..=24"
    );
    // The decimal is read to 120 fractional bits (within 2^-120 of its value) and rounded to
    // `frac_bits` here. A decimal with d <= MAX_DIGITS digits after the point lies either on a
    // tie of the final rounding or at least 1/(10^d * 2^25) > 2^-120 away from every tie, so
    // this one rounding is the correctly rounded result. (Parsing straight to `frac_bits`
    // with fixed 1.31 misrounds: "0.8437" at 4 bits gives 14/16; 0.8437*16 = 13.4992.)
    const MAX_DIGITS: usize = 28;
    let digits = trimmed.split_once('.').map_or(0, |(_, f)| f.len());
    if digits > MAX_DIGITS {
        return Err(err(format!(
            "{text:?} has {digits} digits after the point (at most {MAX_DIGITS})"
        )));
    }
    let wide = trimmed
        .parse::<FixedU128<U120>>()
        .map_err(|e| err(format!("{text:?} does not parse ({e})")))?
        .to_bits();
    let shift = 120 - frac_bits;
    let (q, rem, half) = (
        wide >> shift,
        wide & ((1u128 << shift) - 1),
        1u128 << (shift - 1),
    );
    let code = if rem > half || (rem == half && q & 1 == 1) {
        q + 1
    } else {
        q
    };
    u64::try_from(code).map_err(|_| err(format!("{text:?} is too large")))
}

/// Parses `clock_mhz`: a plain decimal in (0, 1000] MHz.
pub fn parse_clock_mhz(text: &str) -> Result<f64, Error> {
    let bad = |why: String| Error::Config {
        parameter: "clock_mhz",
        message: format!(
            "{why}; allowed a plain decimal in (0, 1000] MHz, such as \"100\" or \"148.5\""
        ),
    };
    let t = text;
    let plain = !t.is_empty()
        && t.len() <= 16
        && t.chars().all(|c| c.is_ascii_digit() || c == '.')
        && t.matches('.').count() <= 1
        && t != ".";
    if !plain {
        return Err(bad(format!("{text:?} is not a plain decimal number")));
    }
    let v: f64 = t
        .parse()
        .map_err(|_| bad(format!("{text:?} does not parse")))?;
    if !(v > 0.0 && v <= 1000.0) {
        return Err(bad(format!("{text:?} is out of range")));
    }
    Ok(v)
}

/// Parses the constant `k` (SPEC §3: `k_q = round(k·2^KF)/2^KF`). Allowed: `0 < k_q ≤ 1`.
pub fn parse_k(text: &str, kf: u32) -> Result<u64, Error> {
    let bad = |why: String| {
        Error::Config {
        parameter: "k",
        message: format!("{why}; allowed a plain decimal such as \"0.3686\" with 0 < k <= 1 after rounding to {kf} fractional bits"),
    }
    };
    // the text goes into file headers as given: no space, line break or other control
    if text.chars().any(|c| c.is_whitespace() || c.is_control()) {
        return Err(bad(format!(
            "{text:?} contains a space, line break or control character"
        )));
    }
    let code = parse_decimal(text, kf).map_err(|e| bad(e.reason()))?;
    if code == 0 {
        return Err(bad(format!("{text:?} rounds to 0")));
    }
    if code > 1u64 << kf {
        return Err(bad(format!("{text:?} is greater than 1")));
    }
    Ok(code)
}
