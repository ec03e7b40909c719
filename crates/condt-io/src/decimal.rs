//! Decimal numbers read without the standard library's general algorithm when that is exact.
//!
//! Kept hand-written because a benchmark shows it earns its place: against `fast-float2` 0.2.4
//! (also correctly rounded, the same bits as `str::parse`), on 1M uniform points of 17-digit
//! shortest round-trip coordinates on one core, `cargo bench -p condt-io --bench parse` gives
//! 45.8 ms for this reader's 2M numbers against 66.7 ms for `fast_float2::parse_partial` (and
//! 140 ms for `str::parse`); with six decimals 22.4 ms against 34.9 ms (87 ms). End to end,
//! `parse_points` (the `parse_text` example, 10 parses of the 38.5 MB file) took 1.62 times the
//! processor time with `fast_float2::parse_partial` in place of this reader, net of reading
//! the file (356 ms against 220 ms, medians of 10 paired runs), and 1.5 times with six
//! decimals.
//!
//! Owns the text readers' number syntax and its conversion to `f64`: every value it returns is
//! the one `str::parse::<f64>` gives for the same bytes, and whatever it declines (more than 19
//! significant digits, a long exponent, an ambiguous rounding, a value out of `f64`'s finite
//! range, other syntax) the caller hands to `str::parse`. The work per number is a few
//! instructions per digit and one or two 64-bit multiplications: digits eight at a time in one
//! machine word, then Clinger's fast path or the Eisel-Lemire product with a 128-bit power of
//! five from a table computed at compile time. Two readers give the same values: the general
//! [`parse_prefix`], and [`parse_prefix_short`] for the common shapes of coordinates, which
//! reads its words at fixed offsets of a 32-byte window and declines the rest to the general
//! one. Neither branches on what varies from number to number in a file of one format (the
//! length of the last run of digits, the mantissa's value), so such branches are not
//! mispredicted.

/// Powers of ten that `f64` holds exactly. A `static`: a `const` array indexed at run time
/// may be copied to the stack at each use.
static POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Most significant digits read into a `u64` (10^19 - 1 < 2^64).
const MAX_DIGITS: usize = 19;

/// Most digits written (leading zeros included) for Clinger's fast path: 10^15 - 1 < 2^53.
const CLINGER_DIGITS: usize = 15;

/// Most digits of a written exponent; longer ones (`1e0000001`) go to `str::parse`.
const MAX_EXPONENT_DIGITS: usize = 5;

/// The value of `[+-]digits[.digits][(e|E)[+-]digits]` (at least one digit before the exponent,
/// as `str::parse` asks) filling all of `bytes`; `None` for what [`parse_prefix`] declines and
/// for anything after the number.
#[inline]
pub(super) fn parse(bytes: &[u8]) -> Option<f64> {
    match parse_prefix(bytes)? {
        (value, []) => Some(value),
        _ => None,
    }
}

/// The number at the start of `text` and the bytes after it: the longest run that has the
/// syntax of [`parse`], rounded to nearest, ties to even, exactly as `str::parse` would round
/// it, and always finite. `None` when no number starts there (no digit), and for what this
/// reader leaves to `str::parse`: more than 19 significant digits, an exponent of more than
/// five digits or without digits (`1e`, `1e+`), an ambiguous Eisel-Lemire product (about one
/// number in 10^19 of uniformly random digits) and results that are not finite.
///
/// The caller decides what may follow the number: the point reader wants a blank or a line end.
/// The text is walked as a shrinking slice, which needs one length check per step.
#[inline(always)]
pub(super) fn parse_prefix(text: &[u8]) -> Option<(f64, &[u8])> {
    let (negative, unsigned) = match text {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, text),
    };
    // Wraps past 19 digits; such a mantissa is used only when the extra digits were leading
    // zeros, which add nothing, so the wrapped values are never used.
    let mut mantissa: u64 = 0;
    let (after_integer, mut digits) = match unsigned {
        // One digit before the point, the most common shape (`0.25`, `1.5e3`): no word to read.
        [d @ b'0'..=b'9', rest @ ..] if rest.first() == Some(&b'.') => {
            mantissa = u64::from(d - b'0');
            (rest, 1)
        }
        _ => {
            let after = read_digits(unsigned, &mut mantissa);
            (after, unsigned.len() - after.len())
        }
    };
    let mut exponent: i64 = 0;
    let mut rest = after_integer;
    if let [b'.', fraction @ ..] = after_integer {
        rest = read_digits(fraction, &mut mantissa);
        let fraction_digits = fraction.len() - rest.len();
        digits += fraction_digits;
        exponent = -(fraction_digits as i64);
    }
    if digits == 0 {
        return None;
    }
    if digits > MAX_DIGITS {
        // Leading zeros (`0.000123`, `007`) are not significant. Counted in the number's own
        // digits: a run of zeros and points may go on past it (`0.000…0.0`, which is no
        // number), and counted there it would exceed `digits`.
        let zeros = unsigned[..unsigned.len() - rest.len()]
            .iter()
            .take_while(|&&b| b == b'0' || b == b'.')
            .filter(|&&b| b == b'0')
            .count();
        if digits - zeros > MAX_DIGITS {
            return None;
        }
    }
    if let [b'e' | b'E', after_e @ ..] = rest {
        let (written, after) = written_exponent(after_e)?;
        exponent += written;
        rest = after;
    }
    let magnitude = convert(mantissa, digits, exponent)?;
    Some((if negative { -magnitude } else { magnitude }, rest))
}

/// The exponent written after an `e`: `[+-]digits`, one to five digits, and the bytes after
/// it; `None` for no digit or more than five.
#[inline(never)]
fn written_exponent(after_e: &[u8]) -> Option<(i64, &[u8])> {
    let (negative, written_digits) = match after_e {
        [b'-', more @ ..] => (true, more),
        [b'+', more @ ..] => (false, more),
        _ => (false, after_e),
    };
    let count = written_digits
        .iter()
        .take(MAX_EXPONENT_DIGITS + 1)
        .take_while(|b| b.is_ascii_digit())
        .count();
    if count == 0 || count > MAX_EXPONENT_DIGITS {
        return None;
    }
    let (written, after) = written_digits.split_at_checked(count)?;
    let written = written
        .iter()
        .fold(0i64, |v, &b| v * 10 + i64::from(b - b'0'));
    Some((if negative { -written } else { written }, after))
}

/// `mantissa * 10^exponent` (`digits` written, leading zeros included, at most 19 significant)
/// rounded as `str::parse` rounds it; `None` where that is left to `str::parse` (an ambiguous
/// Eisel-Lemire product, a result that is not finite).
#[inline(always)]
fn convert(mantissa: u64, digits: usize, exponent: i64) -> Option<f64> {
    Some(if mantissa == 0 {
        0.0
    } else if digits <= CLINGER_DIGITS && exponent.unsigned_abs() <= 22 {
        // Clinger's fast path: the mantissa (below 10^15 < 2^53) and the power of ten are
        // exact in f64, and one correctly rounded multiplication or division gives the result.
        // Chosen by the number of digits written, not by the mantissa's value: in a file of
        // 16- and 17-digit numbers a test of the value would send them this way or the other
        // at random, and the processor would mispredict the branch about once in three.
        let power = POWERS_OF_TEN[exponent.unsigned_abs() as usize];
        if exponent >= 0 {
            mantissa as f64 * power
        } else {
            mantissa as f64 / power
        }
    } else if (i64::from(*NEAR_POWERS.start())..=i64::from(*NEAR_POWERS.end())).contains(&exponent)
    {
        eisel_lemire_near(mantissa, exponent as i32)
    } else if (SMALLEST_POWER..=LARGEST_POWER).contains(&exponent) {
        eisel_lemire(mantissa, exponent as i32)?
    } else {
        return None;
    })
}

/// [`parse_prefix`] for the common shapes of coordinates, `[+-]D[.F][(e|E)exponent]` with one
/// to seven integer digits `D`, up to 23 fraction digits `F` and at most 19 digits in all, at
/// least 32 bytes from the end of the text; `None` for anything else, which the caller then
/// hands to [`parse_prefix`]. Where it answers, it gives exactly what `parse_prefix` gives (the
/// same mantissa, digit count and exponent, the same conversion), in fewer steps: the digits
/// are read as words at fixed offsets from one 32-byte window, so the only branches are on the
/// shape, which the numbers of one file share (how many words the fraction fills).
#[inline(always)]
pub(super) fn parse_prefix_short(text: &[u8]) -> Option<(f64, &[u8])> {
    /// The value of the first `run` (below 8) digits of a word from [`classify`].
    #[inline(always)]
    fn leading(digits: u64, run: usize) -> u64 {
        // As in `read_digits`: the run moved to the top, shifted in two steps.
        value_of_eight_digits((digits << (63 - 8 * run)) << 1)
    }
    /// `mantissa` followed by the eight digits of a word (wrapping past 19 digits, which are
    /// then declined).
    #[inline(always)]
    fn eight(mantissa: u64, digits: u64) -> u64 {
        mantissa
            .wrapping_mul(100_000_000)
            .wrapping_add(value_of_eight_digits(digits))
    }
    /// `mantissa` followed by the leading digits of the word that holds the first byte that is
    /// not a digit, and how many they are.
    #[inline(always)]
    fn last(mantissa: u64, digits: u64, not_digits: u64) -> (u64, usize) {
        /// 10^n for a run of n digits.
        const SCALE: [u64; 8] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000, 10_000_000];
        let run = (not_digits.trailing_zeros() / 8) as usize & 7;
        let mantissa = mantissa
            .wrapping_mul(SCALE[run])
            .wrapping_add(leading(digits, run));
        (mantissa, run)
    }
    let (negative, unsigned) = match text {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, text),
    };
    let window: &[u8; 32] = unsigned.first_chunk::<32>()?;
    #[inline(always)]
    fn word(window: &[u8; 32], at: usize) -> (u64, u64) {
        let word = window
            .get(at..)
            .and_then(<[u8]>::first_chunk::<8>)
            .copied()
            .unwrap_or_default();
        classify(u64::from_le_bytes(word))
    }
    let (mut mantissa, integer) = if window[0].is_ascii_digit() && window[1] == b'.' {
        (u64::from(window[0] - b'0'), 1)
    } else {
        let (digits, not_digits) = word(window, 0);
        // 8 when all eight are digits.
        let run = (not_digits.trailing_zeros() / 8) as usize;
        if run == 0 || run >= 8 {
            return None;
        }
        (leading(digits, run), run)
    };
    let mut fraction = 0;
    let mut end = integer;
    if window[integer & 7] == b'.' {
        let start = integer + 1;
        let (first, first_not) = word(window, start);
        fraction = if first_not != 0 {
            let run;
            (mantissa, run) = last(mantissa, first, first_not);
            run
        } else {
            let (second, second_not) = word(window, start + 8);
            if second_not != 0 {
                let run;
                (mantissa, run) = last(eight(mantissa, first), second, second_not);
                8 + run
            } else {
                let (third, third_not) = word(window, start + 16);
                if third_not == 0 {
                    return None;
                }
                let run;
                (mantissa, run) = last(eight(eight(mantissa, first), second), third, third_not);
                16 + run
            }
        };
        end = start + fraction;
    }
    let digits = integer + fraction;
    if digits > MAX_DIGITS {
        return None;
    }
    let mut exponent = -(fraction as i64);
    let mut rest = unsigned.get(end..)?;
    // `end` is at most 8 + 23 = 31: inside the window.
    if matches!(window[end & 31], b'e' | b'E') {
        let (written, after) = written_exponent(rest.get(1..)?)?;
        exponent += written;
        rest = after;
    }
    let magnitude = convert(mantissa, digits, exponent)?;
    Some((if negative { -magnitude } else { magnitude }, rest))
}

/// [`parse_prefix`] as a call rather than inlined: for the rarer columns, where a copy of its
/// code would only make the caller larger.
#[inline(never)]
pub(super) fn parse_prefix_outlined(text: &[u8]) -> Option<(f64, &[u8])> {
    parse_prefix(text)
}

/// Appends the run of ASCII digits at the start of `text` to `mantissa` (wrapping) and returns
/// the bytes after it, reading eight bytes at a time: a word of eight digits is added whole, and
/// the first word that is not gives the length of its leading run of digits and their value
/// at once. Only the last seven bytes of a text are read one by one.
#[inline(always)]
fn read_digits<'a>(mut text: &'a [u8], mantissa: &mut u64) -> &'a [u8] {
    /// 10^n for a run of n digits.
    const SCALE: [u64; 8] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000, 10_000_000];
    while let Some((word, rest)) = text.split_first_chunk::<8>() {
        let (digits, not_digits) = classify(u64::from_le_bytes(*word));
        if not_digits != 0 {
            // The bytes before the first that is not a digit; fewer than eight.
            let run = not_digits.trailing_zeros() as usize / 8;
            // The run moved to the top of the word, with zero digits below it; no run at all
            // shifts everything out (in two steps: one shift by 64 would be an overflow) and
            // adds nothing. Without a branch on the run, whose length varies from number to
            // number (16 or 17 digits) and would often be mispredicted.
            let top = (digits << (63 - 8 * run)) << 1;
            *mantissa = mantissa
                .wrapping_mul(SCALE[run])
                .wrapping_add(value_of_eight_digits(top));
            return text.get(run..).unwrap_or_default();
        }
        *mantissa = mantissa
            .wrapping_mul(100_000_000)
            .wrapping_add(value_of_eight_digits(digits));
        text = rest;
    }
    while let [b @ b'0'..=b'9', rest @ ..] = text {
        *mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(b - b'0'));
        text = rest;
    }
    text
}

/// For eight bytes read little-endian (the first byte lowest): the bytes minus `'0'`, and the
/// top bit of every byte that is not an ASCII digit. A byte below `'0'` wraps when `'0'` is
/// subtracted, one above `'9'` carries into its top bit when 0x46 is added; a borrow or a carry
/// only moves upward, so the bytes before the first non-digit are marked right and hold their
/// digit's value.
#[inline(always)]
fn classify(word: u64) -> (u64, u64) {
    let digits = word.wrapping_sub(0x3030_3030_3030_3030);
    let above = word.wrapping_add(0x4646_4646_4646_4646);
    (digits, (digits | above) & 0x8080_8080_8080_8080)
}

/// The value of eight digit values 0-9, one a byte, the first (most significant) in the lowest
/// byte: pairs, then fours, then the eight, each step one multiplication of all the lanes at
/// once instead of eight.
#[inline(always)]
fn value_of_eight_digits(digits: u64) -> u64 {
    // Each byte's value times ten plus the next byte's: pairs 0-99 in every other byte. The
    // top byte is at most 9, so the product does not overflow.
    let pairs = (digits * 10 + (digits >> 8)) & 0x00ff_00ff_00ff_00ff;
    // Each 16-bit lane plus 100 times the lane below it (the more significant pair): fours
    // 0-9999 in lanes 1 and 3, moved down to 0 and 2.
    let fours = (pairs.wrapping_mul(1 + (100 << 16)) >> 16) & 0x0000_ffff_0000_ffff;
    // The upper 32-bit lane plus 10^4 times the lower one.
    fours.wrapping_mul(1 + (10_000 << 32)) >> 32
}

/// Smallest decimal exponent of the table: below it, 19 digits round to zero.
const SMALLEST_POWER: i64 = -342;
/// Largest decimal exponent of the table: above it, every nonzero mantissa overflows.
const LARGEST_POWER: i64 = 308;

/// `5^q` for `q` in `SMALLEST_POWER..=LARGEST_POWER` as 128 bits with the top bit set and the
/// binary exponent implied (the Eisel-Lemire table, as the standard library's `dec2flt` has
/// it): for `q >= 0` the top 128 bits of `5^q`, truncated; for `q < 0` the top 128 bits of
/// `2^k / 5^-q`, truncated, plus one when `-27 <= q` (there the table value must be the
/// quotient rounded up for the tie detection below to be exact). `(high, low)` 64-bit halves.
static POWERS_OF_FIVE: [(u64, u64); (LARGEST_POWER - SMALLEST_POWER + 1) as usize] =
    powers_of_five();

/// Limbs of the big numbers that make [`POWERS_OF_FIVE`]: 1024 bits hold `5^308` (716 bits)
/// and `2^1023`, whose quotients by `5^342` (795 bits) still have 228 bits.
const LIMBS: usize = 16;

/// Builds [`POWERS_OF_FIVE`] exactly in multi-limb integers, at compile time: `5^q` by
/// repeated multiplication by 5, and `floor(2^1023 / 5^p)` by repeated division by 5 (the floor
/// of a floor divided by 5 is the floor of the quotient by 5^(p+1)). The top 128 bits of
/// `floor(2^1023 / 5^p)` are `floor(2^(z + 127) / 5^p)` for `z` the bit length of `5^p`,
/// the value the standard library's table generator computes.
const fn powers_of_five() -> [(u64, u64); (LARGEST_POWER - SMALLEST_POWER + 1) as usize] {
    let mut table = [(0u64, 0u64); (LARGEST_POWER - SMALLEST_POWER + 1) as usize];
    let zero_index = (-SMALLEST_POWER) as usize;
    let mut power = [0u64; LIMBS];
    power[0] = 1;
    let mut q = 0;
    while q <= LARGEST_POWER as usize {
        table[zero_index + q] = top_128_bits(&power);
        // times 5
        let mut carry = 0u128;
        let mut k = 0;
        while k < LIMBS {
            let v = power[k] as u128 * 5 + carry;
            power[k] = v as u64;
            carry = v >> 64;
            k += 1;
        }
        q += 1;
    }
    let mut quotient = [0u64; LIMBS];
    quotient[LIMBS - 1] = 1 << 63;
    let mut p = 1;
    while p <= (-SMALLEST_POWER) as usize {
        // divided by 5, from the top limb down
        let mut remainder = 0u128;
        let mut k = LIMBS;
        while k > 0 {
            k -= 1;
            let v = (remainder << 64) | quotient[k] as u128;
            quotient[k] = (v / 5) as u64;
            remainder = v % 5;
        }
        let (high, low) = top_128_bits(&quotient);
        table[zero_index - p] = if p <= 27 {
            // Never carries out: the quotient is not 2^128 - 1.
            let (low, carry) = low.overflowing_add(1);
            (high + carry as u64, low)
        } else {
            (high, low)
        };
        p += 1;
    }
    table
}

/// The 128 bits of `n` (nonzero, little-endian limbs) from its highest set bit down, as
/// `(high, low)` halves, zeros below its lowest bit.
const fn top_128_bits(n: &[u64; LIMBS]) -> (u64, u64) {
    let mut top = LIMBS - 1;
    while n[top] == 0 {
        top -= 1;
    }
    let bits = (top * 64 + 64 - n[top].leading_zeros() as usize) as i64;
    (bits_at(n, bits - 64), bits_at(n, bits - 128))
}

/// Bits `from..from + 64` of `n` as a `u64`; bits below 0 read as zeros.
const fn bits_at(n: &[u64; LIMBS], from: i64) -> u64 {
    let mut word = 0u64;
    let mut k = 0;
    while k < 64 {
        let bit = from + k;
        if bit >= 0 && (n[(bit / 64) as usize] >> (bit % 64)) & 1 == 1 {
            word |= 1 << k;
        }
        k += 1;
    }
    word
}

/// The decimal exponents where [`eisel_lemire`] always decides and its result is a normal
/// number: the table holds `5^q` exactly (`0 <= q <= 55`) or its reciprocal rounded up with
/// room for the carry (`-27 <= q < 0`), and `w * 10^q` for a nonzero `w < 2^64` lies between
/// 10^-27 and 2^64 * 10^55, far inside the normal range of `f64`.
const NEAR_POWERS: core::ops::RangeInclusive<i32> = -27..=55;

/// f64: 52 stored mantissa bits, biased exponent 1 for the smallest normal.
const MANTISSA_BITS: i32 = 52;

/// The exponents where a product can be exactly halfway between two doubles.
const ROUND_TO_EVEN: core::ops::RangeInclusive<i32> = -4..=23;

/// The first step of both Eisel-Lemire conversions: `w` shifted to its top bit, times the
/// 128-bit approximation of `5^q`, as the shift and the product's low and high words. The
/// mantissa and the rounding bit are in the top 55 bits; when the bits below them are all ones,
/// the low half of the power of five may carry into them, and is added.
#[inline(always)]
fn product_with_power_of_five(w: u64, q: i32) -> (u32, u64, u64) {
    let zeros = w.leading_zeros();
    let w = w << zeros;
    let (high5, low5) = POWERS_OF_FIVE[(i64::from(q) - SMALLEST_POWER) as usize];
    let first = u128::from(w) * u128::from(high5);
    let (mut low, mut high) = (first as u64, (first >> 64) as u64);
    let mask = u64::MAX >> (MANTISSA_BITS + 3);
    if high & mask == mask {
        let second = ((u128::from(w) * u128::from(low5)) >> 64) as u64;
        low = low.wrapping_add(second);
        if second > low {
            high += 1;
        }
    }
    (zeros, low, high)
}

/// The 55-bit `mantissa` (its last bit the rounding bit) of the product's `high` word rounded
/// to 54 bits, to nearest; exactly halfway (the product is exact and the dropped bits are one
/// then zeros) to even, by not rounding the odd mantissa up. Both conversions end so.
#[inline(always)]
fn round_half_to_even(mut mantissa: u64, low: u64, high: u64, q: i32, upper_bit: i32) -> u64 {
    if low <= 1
        && ROUND_TO_EVEN.contains(&q)
        && mantissa & 3 == 1
        && (mantissa << (upper_bit + 64 - MANTISSA_BITS - 3)) == high
    {
        mantissa &= !1;
    }
    mantissa += mantissa & 1;
    mantissa >> 1
}

/// [`eisel_lemire`] for `q` in [`NEAR_POWERS`] (`w` nonzero), without the steps that cannot
/// happen there (no ambiguous product, no subnormal, no overflow: always a result), and the
/// carry of the rounding into the exponent taken by adding the fields instead of by a branch.
/// Inlined into the number reader: the common numbers' conversion, about 25 instructions.
#[inline(always)]
fn eisel_lemire_near(w: u64, q: i32) -> f64 {
    debug_assert!(w != 0 && NEAR_POWERS.contains(&q));
    let (zeros, low, high) = product_with_power_of_five(w, q);
    // Both factors have their top bit set: `high` has bit 63 or 62, and `mantissa` 54 bits.
    let upper_bit = (high >> 63) as i32;
    let mantissa = high >> (upper_bit + 64 - MANTISSA_BITS - 3);
    let power_of_ten_bits = ((q.wrapping_mul(152_170 + 65_536)) >> 16) + 63;
    // At least 1023 - 90 here: a normal number.
    let power2 = power_of_ten_bits + upper_bit - zeros as i32 + 1023;
    let mantissa = round_half_to_even(mantissa, low, high, q, upper_bit);
    // 2^52 <= mantissa <= 2^53: its implicit bit adds one to the exponent field below it, and
    // a rounding that reached 2^53 adds two, with a zero fraction, as it should.
    f64::from_bits((((power2 - 1) as u64) << MANTISSA_BITS) + mantissa)
}

/// `w * 10^q` rounded to nearest, ties to even (`w` nonzero, `q` in the table's range), by the
/// Eisel-Lemire algorithm (Lemire, "Number parsing at a gigabyte per second", 2021, and the
/// standard library's `dec2flt::lemire`, which this follows step for step): the product of `w`
/// and the 128-bit approximation of `5^q` decides the rounding unless its low bits are too
/// close to a halfway point to tell (`None`, about one number in 10^19, left to `str::parse`).
/// `None` too for a result too large for `f64`.
#[inline]
fn eisel_lemire(w: u64, q: i32) -> Option<f64> {
    const INFINITE_POWER: i32 = 0x7ff;
    let (zeros, low, high) = product_with_power_of_five(w, q);
    // Still all ones: the truncated table value may have hidden a carry, except where 5^q is
    // exact in 128 bits (0 <= q <= 55) or its reciprocal leaves room (q >= -27).
    if low == u64::MAX && !(-27..=55).contains(&q) {
        return None;
    }
    let upper_bit = (high >> 63) as i32;
    let mut mantissa = high >> (upper_bit + 64 - MANTISSA_BITS - 3);
    // floor(log2(10^q)) + 63, plus the normalisation, plus the exponent bias 1023.
    let power_of_ten_bits = ((q.wrapping_mul(152_170 + 65_536)) >> 16) + 63;
    let mut power2 = power_of_ten_bits + upper_bit - zeros as i32 + 1023;
    if power2 <= 0 {
        // A subnormal, or zero.
        if -power2 + 1 >= 64 {
            return Some(0.0);
        }
        mantissa >>= -power2 + 1;
        mantissa += mantissa & 1;
        mantissa >>= 1;
        // Rounding up may reach the smallest normal: its exponent field is then 1.
        let biased = u64::from(mantissa >= 1 << MANTISSA_BITS);
        return Some(f64::from_bits(mantissa | (biased << MANTISSA_BITS)));
    }
    mantissa = round_half_to_even(mantissa, low, high, q, upper_bit);
    if mantissa >= 2 << MANTISSA_BITS {
        // Rounding carried into a new bit.
        mantissa = 1 << MANTISSA_BITS;
        power2 += 1;
    }
    mantissa &= !(1 << MANTISSA_BITS);
    if power2 >= INFINITE_POWER {
        return None;
    }
    Some(f64::from_bits(
        mantissa | ((power2 as u64) << MANTISSA_BITS),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::test_rng::Xorshift;

    /// `parse` either declines or gives the bits `str::parse` gives; returns whether it took it.
    fn agrees(text: &str) -> bool {
        let standard = text.parse::<f64>().ok();
        match parse(text.as_bytes()) {
            None => false,
            Some(fast) => {
                let standard = standard.unwrap_or_else(|| panic!("{text:?} is not a number"));
                assert_eq!(fast.to_bits(), standard.to_bits(), "{text:?}");
                true
            }
        }
    }

    #[test]
    fn the_table_matches_the_standard_librarys_generator() {
        // Entries computed with Python's integers by the generator of the standard library's
        // table (src/etc/dec2flt_table.py), at the ends and at the changes of rule.
        let expected: [(i64, u64, u64); 17] = [
            (-342, 0xeef453d6923bd65a, 0x113faa2906a13b3f),
            (-341, 0x9558b4661b6565f8, 0x4ac7ca59a424c507),
            (-300, 0xab70fe17c79ac6ca, 0x6dbd630a48aaf406),
            (-100, 0xdff9772470297ebd, 0x59787e2b93bc56f7),
            (-28, 0xfd87b5f28300ca0d, 0x8bca9d6e188853fc),
            (-27, 0x9e74d1b791e07e48, 0x775ea264cf55347e),
            (-26, 0xc612062576589dda, 0x95364afe032a819e),
            (-1, 0xcccccccccccccccc, 0xcccccccccccccccd),
            (0, 0x8000000000000000, 0x0000000000000000),
            (1, 0xa000000000000000, 0x0000000000000000),
            (27, 0xcecb8f27f4200f3a, 0x0000000000000000),
            (28, 0x813f3978f8940984, 0x4000000000000000),
            (55, 0xd0cf4b50cfe20765, 0xfff4b4e3f741cf6d),
            (56, 0x82818f1281ed449f, 0xbff8f10e7a8921a4),
            (100, 0x924d692ca61be758, 0x593c2626705f9c56),
            (307, 0xe3d8f9e563a198e5, 0x58180fddd97723a6),
            (308, 0x8e679c2f5e44ff8f, 0x570f09eaa7ea7648),
        ];
        for (q, high, low) in expected {
            let entry = POWERS_OF_FIVE[(q - SMALLEST_POWER) as usize];
            assert_eq!(entry, (high, low), "5^{q}");
        }
        // Every entry is normalised, and consecutive powers differ by a factor of 5 (about
        // 1.25 times a power of two), which a wrong limb or shift would break.
        for (k, pair) in POWERS_OF_FIVE.windows(2).enumerate() {
            let (a, b) = (pair[0].0, pair[1].0);
            assert!(a >> 63 == 1 && b >> 63 == 1, "{k}");
            let ratio = b as f64 / a as f64;
            assert!(
                (ratio - 1.25).abs() < 1e-9 || (ratio - 0.625).abs() < 1e-9,
                "{k}: {ratio}"
            );
        }
    }

    #[test]
    fn a_word_at_a_time_reads_what_one_byte_at_a_time_reads() {
        let mut stream = Xorshift::new(0x1234_5678_9abc_def1);
        let mut words: Vec<[u8; 8]> = vec![*b"00000000", *b"99999999", *b"12345678", [0; 8]];
        for _ in 0..200_000 {
            let mut word = [0u8; 8];
            for b in &mut word {
                // Mostly digits, sometimes the bytes just outside them, sometimes any byte.
                *b = match stream.below(10) {
                    0 => [b'/', b':', b'.', b' ', 0, 0xff, b'0' - 1][stream.below(7) as usize],
                    1 => stream.next_u64() as u8,
                    _ => b'0' + stream.below(10) as u8,
                };
            }
            words.push(word);
        }
        for word in words {
            let run = word.iter().take_while(|b| b.is_ascii_digit()).count();
            let (digits, not_digits) = classify(u64::from_le_bytes(word));
            assert_eq!(not_digits == 0, run == 8, "{word:?}");
            // The first byte marked is the first that is not a digit.
            assert_eq!((not_digits.trailing_zeros() / 8) as usize, run, "{word:?}");
            if run == 8 {
                let one_by_one = word.iter().fold(0u64, |v, &b| v * 10 + u64::from(b - b'0'));
                assert_eq!(value_of_eight_digits(digits), one_by_one, "{word:?}");
            }
            // Through `read_digits`, with more digits after the word, and at the end of a text.
            let mut longer = word.to_vec();
            longer.extend_from_slice(b"12x");
            for cut in (0..=8).chain([10, 11]) {
                let mut mantissa = 7;
                let end = cut - read_digits(&longer[..cut], &mut mantissa).len();
                let expected = longer[..cut]
                    .iter()
                    .take_while(|b| b.is_ascii_digit())
                    .fold(7u64, |v, &b| v.wrapping_mul(10) + u64::from(b - b'0'));
                let expected_end = longer[..cut]
                    .iter()
                    .take_while(|b| b.is_ascii_digit())
                    .count();
                assert_eq!((end, mantissa), (expected_end, expected), "{word:?} {cut}");
            }
        }
        let long = "1234567890".repeat(3);
        let mut mantissa = 0;
        assert!(read_digits(&long.as_bytes()[11..], &mut mantissa).is_empty());
        assert_eq!(mantissa, 2345678901234567890);
    }

    #[test]
    fn the_fast_path_gives_what_str_parse_gives_or_declines() {
        let cases = [
            "0",
            "-0",
            "+0",
            "1",
            "-1.5",
            "0.1",
            "3.14159",
            "1e22",
            "1e-22",
            "1e23",
            "9007199254740992",
            "9007199254740993",
            "0.9371698010707118",
            "123456.789e-3",
            ".5",
            "5.",
            "-.5e+2",
            "1e",
            "e5",
            "1.2.3",
            "--1",
            "+-1",
            "1e+",
            "1e-",
            "1E5",
            "inf",
            "NaN",
            "0x10",
            "",
            "-",
            "+",
            ".",
            "-.",
            ".e1",
            "1 ",
            " 1",
            "1_0",
            "00000000000000000000000000001",
            "0.00000000000000000000000000001234567890123456789",
            "0000000000000000000012345678901234567890",
            "1e0000001",
            "1e00001",
            "4.35",
            "0.30000000000000004",
            "1.7976931348623157e308",
            "1.7976931348623158e308",
            "1.7976931348623159e308",
            "1e308",
            "1e309",
            "2.2250738585072011e-308",
            "2.2250738585072014e-308",
            "4.9406564584124654e-324",
            "2.4703282292062327e-324",
            "2.4703282292062328e-324",
            "5e-324",
            "1e-400",
            "0e999",
            "8.98846567431158e307",
            // More than 19 digits, all zeros, then a second point and a zero (found by
            // fuzzing: the zeros were counted past the number, more of them than its digits);
            // the middle one, a point and a nonzero digit, never overflowed (a control).
            "0.0000000000000000000.0",
            "0.00000000000000000000.5",
            "000000000000000000000.0.0",
        ];
        for case in cases {
            agrees(case);
        }
        // The number ends at the second point: zero, with the rest left to the caller.
        let zero = parse_prefix(b"0.0000000000000000000.0 1").map(|(v, rest)| (v.to_bits(), rest));
        assert_eq!(zero, Some((0u64, &b".0 1"[..])));
        // The common forms and the edges of the table do take the fast path.
        for case in [
            "0",
            "-1.5",
            "0.1",
            "1e22",
            "123456.789e-3",
            ".5",
            "5.",
            "-.5e+2",
            "0.13436424411240122",
            "1.7976931348623157e308",
            "2.2250738585072014e-308",
            "4.9406564584124654e-324",
            "0.00000000000000000000000000001234567890123456789",
            "0e999",
        ] {
            assert!(parse(case.as_bytes()).is_some(), "{case}");
        }
        // Declined: too many digits, a long exponent, overflow, bad syntax.
        for case in [
            "12345678901234567890",
            "1e000001",
            "1e309",
            "1.7976931348623159e308",
            "1e",
            ".",
            "1 ",
        ] {
            assert!(parse(case.as_bytes()).is_none(), "{case}");
        }
    }

    #[test]
    fn random_decimals_of_1_to_20_digits_parse_as_str_parse_does() {
        let mut stream = Xorshift::new(0x2545_f491_4f6c_dd1d);
        let mut taken = 0;
        let mut text = String::new();
        let total = 2_000_000;
        for _ in 0..total {
            text.clear();
            match stream.below(3) {
                0 => {}
                1 => text.push('-'),
                _ => text.push('+'),
            }
            for _ in 0..[0, 0, 1, 5][stream.below(4) as usize] {
                text.push('0');
            }
            let digits = 1 + stream.below(20) as usize;
            // Where the point goes: nowhere, or after any digit, or before them all.
            let point = stream.below(digits as u64 + 2) as usize;
            for d in 0..digits {
                if d == point {
                    text.push('.');
                }
                text.push(char::from(b'0' + stream.below(10) as u8));
            }
            if point == digits {
                text.push('.');
            }
            match stream.below(4) {
                0 => {}
                // Small exponents, where Clinger's path and the exact ties are.
                1 => text.push_str(&format!("e{}", stream.below(50) as i64 - 25)),
                // The whole range of f64 and beyond it, subnormals and overflow included.
                2 => text.push_str(&format!("E{}", stream.below(700) as i64 - 350)),
                _ => text.push_str(&format!("e+{}", stream.below(30))),
            }
            if agrees(&text) {
                taken += 1;
            }
        }
        assert!(taken * 10 > total * 6, "{taken} of {total}");
    }

    #[test]
    fn shortest_and_long_forms_of_random_doubles_parse_as_str_parse_does() {
        let mut stream = Xorshift::new(0x9e37_79b9_7f4a_7c15);
        for k in 0..300_000 {
            // Any finite double: random bits, normals and subnormals alike.
            let value =
                f64::from_bits(stream.next_u64() & !(0x7ff << 52) | (stream.below(2047) << 52));
            let decimals = [16, 17, 18, 19][k % 4];
            for text in [
                format!("{value}"),
                format!("{value:e}"),
                format!("{value:.decimals$e}"),
            ] {
                agrees(&text);
            }
            // Shortest forms always have at most 17 digits: the fast path must take them.
            let shortest = format!("{value:e}");
            let back = parse(shortest.as_bytes())
                .unwrap_or_else(|| panic!("declined the shortest form {shortest}"));
            assert_eq!(back.to_bits(), value.to_bits(), "{shortest}");
        }
    }

    #[test]
    fn halfway_cases_and_boundaries_round_to_even() {
        let mut cases: Vec<String> = Vec::new();
        // Around 2^53: 2^53 + 1 and + 3 are halfway between doubles.
        for offset in 0..8u64 {
            cases.push(format!("{}", (1u64 << 53) + offset));
            cases.push(format!("{}", (1u64 << 54) + offset));
            cases.push(format!("{}", (1u64 << 53) - offset));
            cases.push(format!("{}e0", (1u64 << 53) + offset));
            cases.push(format!("{}0e-1", (1u64 << 53) + offset));
        }
        // Exact halfway points between consecutive doubles, (2m + 1) * 2^(s - 1) for a 53-bit
        // m, written in full with at most 19 digits: s from -3 to 1 (digits after the point).
        let mut stream = Xorshift::new(0x0123_4567_89ab_cdef);
        for _ in 0..20_000 {
            let twice = 2 * ((1u64 << 52) | stream.next_u64() >> 12) + 1;
            let shift = stream.below(4) as u32;
            let text = if shift == 0 {
                format!("{twice}")
            } else {
                // twice / 2^shift = twice * 5^shift / 10^shift
                let digits = (u128::from(twice) * 5u128.pow(shift)).to_string();
                let cut = digits.len() - shift as usize;
                format!("{}.{}", &digits[..cut], &digits[cut..])
            };
            cases.push(text);
        }
        // Halfway points t * 10^q with 0 <= q <= 23: t * 5^q is an odd 54-bit number.
        for q in 0..=23u32 {
            let five = 5u128.pow(q);
            let (low, high) = ((1u128 << 53) / five + 1, (1u128 << 54) / five);
            for _ in 0..200 {
                let t = (low + u128::from(stream.next_u64()) % (high - low + 1)) | 1;
                if t * five < 1 << 54 {
                    cases.push(format!("{t}e{q}"));
                    cases.push(format!("{t}{}", "0".repeat(q as usize)));
                }
            }
        }
        // Just above and below the largest double, the smallest normal and subnormals.
        for text in [
            "1.7976931348623157e308",
            "1.7976931348623158e308",
            "2.225073858507201e-308",
            "2.2250738585072011e-308",
            "2.2250738585072012e-308",
            "2.2250738585072013e-308",
            "4.9406564584124654e-324",
            "7.4109846876186982e-324",
            "2.4703282292062328e-324",
            "1.2e-320",
            "9.8813129168249309e-324",
        ] {
            cases.push(text.to_string());
        }
        for text in &cases {
            agrees(text);
        }
        let taken = cases
            .iter()
            .filter(|t| parse(t.as_bytes()).is_some())
            .count();
        assert!(taken * 10 > cases.len() * 7, "{taken} of {}", cases.len());
    }

    #[test]
    fn the_near_conversion_is_the_general_one_and_str_parses() {
        let mut stream = Xorshift::new(0x6c07_8965_9d2c_3a1b);
        let mut checked = 0;
        for q in NEAR_POWERS {
            let mut ws: Vec<u64> = vec![1, 9, 10, u64::MAX, 1 << 53, (1 << 53) + 1, (1 << 54) - 1];
            for _ in 0..3000 {
                // Every length of mantissa, and ones with many trailing zero bits or ones.
                let bits = 1 + stream.below(64) as u32;
                let w = stream.next_u64() >> (64 - bits);
                ws.push(w.max(1));
                ws.push((w | 1) << stream.below(u64::from(64 - bits.min(63))));
                ws.push(w | ((1u64 << stream.below(12)) - 1));
            }
            // Halfway between two doubles when q is small: (2m + 1) * 2^k / 10^q exactly.
            if (0..=19).contains(&q) {
                for _ in 0..200 {
                    let twice = 2 * ((1u64 << 52) | stream.next_u64() >> 12) + 1;
                    if let Some(w) = twice.checked_shl(stream.below(10) as u32) {
                        if w >> stream.below(10) != 0 {
                            ws.push(w);
                        }
                    }
                }
            }
            for w in ws.into_iter().filter(|&w| w != 0) {
                let near = eisel_lemire_near(w, q);
                let general = eisel_lemire(w, q).expect("decides in the near range");
                let standard: f64 = format!("{w}e{q}").parse().unwrap();
                assert_eq!(near.to_bits(), general.to_bits(), "{w}e{q}");
                assert_eq!(near.to_bits(), standard.to_bits(), "{w}e{q}");
                checked += 1;
            }
        }
        assert!(checked > 83 * 9000, "{checked}");
    }

    #[test]
    fn the_short_reader_gives_what_parse_prefix_gives_or_declines() {
        let mut stream = Xorshift::new(0x3c6e_f372_fe94_f82b);
        let digit = |stream: &mut Xorshift| char::from(b'0' + stream.below(10) as u8);
        let (mut taken, total) = (0, 400_000);
        let mut text = String::new();
        for k in 0..total {
            text.clear();
            match stream.below(4) {
                0 => text.push('-'),
                1 => text.push('+'),
                _ => {}
            }
            // Integer digits 0 to 9, fraction digits 0 to 25 or no point at all.
            for _ in 0..[1, 1, 1, 0, 2, 3, 7, 8, 9][stream.below(9) as usize] {
                text.push(digit(&mut stream));
            }
            if stream.below(12) > 0 {
                text.push('.');
                let fraction = match stream.below(3) {
                    0 => stream.below(26),
                    _ => 14 + stream.below(6),
                };
                for _ in 0..fraction {
                    // Now and then all zeros, for the zero and the leading-zero cases.
                    text.push(if k % 7 == 0 { '0' } else { digit(&mut stream) });
                }
            }
            // What follows: a blank, a line end, an exponent, another point, a digit after a
            // gap, a letter.
            let after = [" 0.5", "\n", "e5", "E-3", ".5", "x", "\t1", ",2", "e"];
            text.push_str(after[stream.below(after.len() as u64) as usize]);
            // Padding to the window's 32 bytes (or not: too short is declined).
            if stream.below(8) > 0 {
                text.push_str(&" 1.5".repeat(10));
            }
            let bytes = text.as_bytes();
            if let Some((value, rest)) = parse_prefix_short(bytes) {
                let (expected, expected_rest) = parse_prefix(bytes)
                    .unwrap_or_else(|| panic!("{text:?}: the short reader took it alone"));
                assert_eq!(value.to_bits(), expected.to_bits(), "{text:?}");
                assert_eq!(rest, expected_rest, "{text:?}");
                taken += 1;
            }
        }
        assert!(taken * 5 > total, "{taken} of {total}");
        // The common coordinate forms are taken, with the window's room after them.
        let room = " ".repeat(32);
        for case in [
            "0.13436424411240122",
            "0.5118216247002567",
            "0.012345678901234567",
            "-0.25",
            "123.456789",
            "5.",
            "1234567.0",
            "1.5e3",
            "-2.5E-300",
            "42",
            "7e+22",
            "0.12345678901234567e2",
        ] {
            let text = format!("{case}{room}");
            let (value, rest) = parse_prefix_short(text.as_bytes()).expect(case);
            assert_eq!(value, case.parse::<f64>().unwrap(), "{case}");
            assert_eq!(rest.len(), room.len(), "{case}");
        }
        // Declined, for `parse_prefix`: no integer digit, 8 integer digits, more than 19
        // digits, too close to the end, a bad exponent.
        for case in [
            ".5",
            "12345678.5",
            "0.1234567890123456789",
            "0.5",
            "1.5e",
            "2e123456",
        ] {
            let text = if case == "0.5" {
                format!("{case} 1")
            } else {
                format!("{case}{room}")
            };
            assert!(parse_prefix_short(text.as_bytes()).is_none(), "{case}");
        }
    }

    #[test]
    fn a_prefix_ends_where_the_number_does() {
        assert_eq!(parse_prefix(b"1.5 2"), Some((1.5, &b" 2"[..])));
        assert_eq!(parse_prefix(b"-2e1\n"), Some((-20.0, &b"\n"[..])));
        assert_eq!(parse_prefix(b"-2e+1x"), Some((-20.0, &b"x"[..])));
        assert_eq!(
            parse_prefix(b"12345678901234567x"),
            Some((12345678901234567.0, &b"x"[..]))
        );
        assert_eq!(parse_prefix(b"7e"), None);
        assert_eq!(parse_prefix(b"7e123456"), None);
        assert_eq!(parse_prefix(b" 7"), None);
        assert_eq!(parse_prefix(b""), None);
    }
}
