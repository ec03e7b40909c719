//! Exact signs by integer arithmetic, for coordinates whose spread of magnitudes Shewchuk's
//! floating-point expansions cannot take without underflow: integers below `2^2098` in units of
//! the call's smallest exponent, determinants below `2^8400` in 64-bit limbs on the stack, as
//! few as the call's spread needs (`docs/predicates.md`, item 3). Microseconds at worst:
//! [`super`] runs it only where needed.
//!
//! Owns: the big-integer reading of a call's coordinates and its determinants. It may not decide
//! when it runs (the filters in [`super`] do) and uses no floating-point arithmetic for a sign.

use core::cmp::Ordering;

/// Limbs for the largest intermediate value, `2^8400` (132 limbs), plus a spare so that an
/// addition's carry never needs a check against the end.
const LIMBS: usize = 134;

/// Calls `$function::<L>(..)` with the narrowest `L` of 8, 16, 32 or 64 limbs that is at least
/// `$limbs`, else with the full width: every operation copies its `Int` (about 1 KB at full
/// width), which made the copies most of the time on sets spanning many binary orders.
///
/// Stack: the widths of 32 limbs and more run in frames of their own ([`apart`]), and the signs
/// are never inlined into the predicates of [`super`], so a call holds the integers of the
/// width it uses, only while it runs (an embedded review found `in_circle`'s frame at 32.6 KB,
/// the full width's, reserved by every call; a wide set wrote 64 KB of stack, now 31.5 KB).
macro_rules! in_width {
    ($limbs:expr, $function:ident($($arg:expr),*)) => {
        match $limbs {
            0..=8 => $function::<8>($($arg),*),
            9..=16 => $function::<16>($($arg),*),
            17..=32 => apart(|| $function::<32>($($arg),*)),
            33..=64 => apart(|| $function::<64>($($arg),*)),
            _ => apart(|| $function::<LIMBS>($($arg),*)),
        }
    };
}

/// `work()` in a frame of its own: the integers of 32 limbs and more (8 to 32 KB of stack for a
/// predicate's temporaries) are held only while such a call runs, not by every caller of the
/// width switch (see [`in_width`]).
#[inline(never)]
fn apart<R>(work: impl FnOnce() -> R) -> R {
    work()
}

/// A signed integer of at most `64 · L` bits, as sign and magnitude.
#[derive(Clone, Copy)]
struct Int<const L: usize = LIMBS> {
    negative: bool,
    /// Limbs in use, least significant first; `limbs[len - 1] != 0` unless `len == 0` (zero).
    len: usize,
    limbs: [u64; L],
}

impl<const L: usize> Int<L> {
    const ZERO: Int<L> = Int {
        negative: false,
        len: 0,
        limbs: [0; L],
    };

    /// `x / 2^e0` as an integer; `e0` must be at most the exponent of `x`'s last set bit.
    fn from_f64(x: f64, e0: i32) -> Int<L> {
        let Some((negative, mantissa, exponent)) = decompose(x) else {
            return Int::ZERO;
        };
        let shift = (exponent - e0) as usize;
        debug_assert!(exponent >= e0 && shift + 53 <= 64 * (L - 1));
        let mut out = Int::ZERO;
        let (word, bit) = (shift / 64, shift % 64);
        out.limbs[word] = mantissa << bit;
        if bit != 0 {
            out.limbs[word + 1] = mantissa >> (64 - bit);
        }
        out.negative = negative;
        out.len = word + 2;
        out.trim();
        out
    }

    fn trim(&mut self) {
        while self.len > 0 && self.limbs[self.len - 1] == 0 {
            self.len -= 1;
        }
        if self.len == 0 {
            self.negative = false;
        }
    }

    fn magnitude(&self) -> &[u64] {
        &self.limbs[..self.len]
    }
    fn signum(&self) -> Ordering {
        match (self.len, self.negative) {
            (0, _) => Ordering::Equal,
            (_, true) => Ordering::Less,
            (_, false) => Ordering::Greater,
        }
    }

    fn negated(mut self) -> Int<L> {
        self.negative = !self.negative && self.len > 0;
        self
    }

    fn add(&self, other: &Int<L>) -> Int<L> {
        if self.negative == other.negative {
            let mut sum = add_magnitudes::<L>(self.magnitude(), other.magnitude());
            sum.negative = self.negative && sum.len > 0;
            return sum;
        }
        let (large, small) = match compare_magnitudes(self.magnitude(), other.magnitude()) {
            Ordering::Equal => return Int::ZERO,
            Ordering::Greater => (self, other),
            Ordering::Less => (other, self),
        };
        let mut difference = subtract_magnitudes::<L>(large.magnitude(), small.magnitude());
        difference.negative = large.negative;
        difference
    }

    fn sub(&self, other: &Int<L>) -> Int<L> {
        self.add(&other.negated())
    }
    fn mul(&self, other: &Int<L>) -> Int<L> {
        let (a, b) = (self.magnitude(), other.magnitude());
        if a.is_empty() || b.is_empty() {
            return Int::ZERO;
        }
        debug_assert!(a.len() + b.len() <= L);
        let mut out = Int::ZERO;
        for (i, &x) in a.iter().enumerate() {
            let mut carry = 0u64;
            for (j, &y) in b.iter().enumerate() {
                let t = u128::from(x) * u128::from(y)
                    + u128::from(out.limbs[i + j])
                    + u128::from(carry);
                out.limbs[i + j] = t as u64;
                carry = (t >> 64) as u64;
            }
            out.limbs[i + b.len()] = carry;
        }
        out.len = a.len() + b.len();
        out.negative = self.negative != other.negative;
        out.trim();
        out
    }
}

/// `x = ±m · 2^e` with `m` odd, or `None` for zero.
fn decompose(x: f64) -> Option<(bool, u64, i32)> {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let fraction = bits & ((1u64 << 52) - 1);
    let (mantissa, exponent) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1u64 << 52), biased - 1075)
    };
    if mantissa == 0 {
        return None;
    }
    let zeros = mantissa.trailing_zeros();
    Some((bits >> 63 == 1, mantissa >> zeros, exponent + zeros as i32))
}

/// The points' coordinates as integers in units of `2^e0`, `e0` the exponent of the last set bit
/// of the least precise one (zero when all are zero): each is an integer multiple of `2^e0`.
fn integers<const N: usize, const L: usize>(points: [[f64; 2]; N]) -> [[Int<L>; 2]; N] {
    let e0 = least_exponent(&points);
    points.map(|p| p.map(|c| Int::from_f64(c, e0)))
}

/// [`integers`]' unit: the exponent of the last set bit of the least precise coordinate (zero
/// when all are zero).
fn least_exponent(points: &[[f64; 2]]) -> i32 {
    let exponents = points.as_flattened().iter().filter_map(|&c| decompose(c));
    exponents.map(|(_, _, e)| e).min().unwrap_or(0)
}

fn compare_magnitudes(a: &[u64], b: &[u64]) -> Ordering {
    a.len()
        .cmp(&b.len())
        .then_with(|| a.iter().rev().cmp(b.iter().rev()))
}

fn add_magnitudes<const L: usize>(a: &[u64], b: &[u64]) -> Int<L> {
    let (long, short) = if a.len() >= b.len() { (a, b) } else { (b, a) };
    let mut out = Int::ZERO;
    let mut carry = false;
    for (i, &x) in long.iter().enumerate() {
        let y = short.get(i).copied().unwrap_or(0);
        let (s, c1) = x.overflowing_add(y);
        let (s, c2) = s.overflowing_add(u64::from(carry));
        out.limbs[i] = s;
        carry = c1 || c2;
    }
    out.limbs[long.len()] = u64::from(carry);
    out.len = long.len() + 1;
    out.trim();
    out
}

/// `a - b` for `a >= b`.
fn subtract_magnitudes<const L: usize>(a: &[u64], b: &[u64]) -> Int<L> {
    let mut out = Int::ZERO;
    let mut borrow = false;
    for (i, &x) in a.iter().enumerate() {
        let y = b.get(i).copied().unwrap_or(0);
        let (d, b1) = x.overflowing_sub(y);
        let (d, b2) = d.overflowing_sub(u64::from(borrow));
        out.limbs[i] = d;
        borrow = b1 || b2;
    }
    debug_assert!(!borrow, "subtracting a larger magnitude");
    out.len = a.len();
    out.trim();
    out
}

/// The exact orientation sign: `Greater` when `a, b, c` turn counter-clockwise.
#[inline(never)]
pub(crate) fn orient2d_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
    // Two products of two differences, their difference, and a spare limb for a carry.
    let limbs = difference_limbs(integer_bits(&[a, b, c]));
    in_width!(2 * limbs + 2, orient2d_in(a, b, c))
}

/// [`orient2d_sign`] in integers of `L` limbs.
fn orient2d_in<const L: usize>(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
    let [[ax, ay], [bx, by], [cx, cy]] = integers::<3, L>([a, b, c]);
    let (acx, acy) = (ax.sub(&cx), ay.sub(&cy));
    let (bcx, bcy) = (bx.sub(&cx), by.sub(&cy));
    acx.mul(&bcy).sub(&acy.mul(&bcx)).signum()
}

/// The exact in-circle sign: `Greater` when `d` is strictly inside the circle through the
/// counter-clockwise `a, b, c`, `Equal` when the four are cocircular.
#[inline(never)]
pub(crate) fn in_circle_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Ordering {
    // A lift (a sum of two squares, one limb over them) times a 2x2 determinant (one over its
    // products), a sum of three such, and a spare limb for a carry.
    let limbs = difference_limbs(integer_bits(&[a, b, c, d]));
    in_width!(4 * limbs + 4, in_circle_in(a, b, c, d))
}

/// [`in_circle_sign`] in integers of `L` limbs.
fn in_circle_in<const L: usize>(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Ordering {
    let [a, b, c, [dx, dy]] = integers::<4, L>([a, b, c, d]);
    let relative = |[x, y]: [Int<L>; 2]| (x.sub(&dx), y.sub(&dy));
    let ((adx, ady), (bdx, bdy), (cdx, cdy)) = (relative(a), relative(b), relative(c));
    let lift = |x: &Int<L>, y: &Int<L>| x.mul(x).add(&y.mul(y));
    let (alift, blift, clift) = (lift(&adx, &ady), lift(&bdx, &bdy), lift(&cdx, &cdy));
    let bc = bdx.mul(&cdy).sub(&bdy.mul(&cdx));
    let ca = cdx.mul(&ady).sub(&cdy.mul(&adx));
    let ab = adx.mul(&bdy).sub(&ady.mul(&bdx));
    alift
        .mul(&bc)
        .add(&blift.mul(&ca))
        .add(&clift.mul(&ab))
        .signum()
}

/// The exact sign of the dot product `(a - b) · (c - d)`.
#[inline(never)]
pub(crate) fn dot_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Ordering {
    // As [`orient2d_sign`]: two products of two differences, their sum, a spare limb.
    let limbs = difference_limbs(integer_bits(&[a, b, c, d]));
    in_width!(2 * limbs + 2, dot_in(a, b, c, d))
}

/// [`dot_sign`] in integers of `L` limbs.
fn dot_in<const L: usize>(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Ordering {
    let [[ax, ay], [bx, by], [cx, cy], [dx, dy]] = integers::<4, L>([a, b, c, d]);
    let (ux, uy, vx, vy) = (ax.sub(&bx), ay.sub(&by), cx.sub(&dx), cy.sub(&dy));
    ux.mul(&vx).add(&uy.mul(&vy)).signum()
}

/// The exact order of `|a - p|` and `|b - p|`. Evenly spaced samples whose coordinates are not
/// dyadic (0.1 apart) tie when rounded at almost every point, so this runs once per point there:
/// in machine integers, or in as few limbs as the coordinates allow.
#[inline(never)]
pub(crate) fn compare_distances(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> Ordering {
    let bits = integer_bits(&[p, a, b]);
    if bits <= 62 {
        return compare_distances_u128(p, a, b);
    }
    // Two squares of differences, each sum one limb over them, and a spare limb for a carry.
    in_width!(
        2 * difference_limbs(bits) + 2,
        compare_distances_in(p, a, b)
    )
}

/// The exact order of `scale · |a - p|` against `|b - p|` (`scale` positive and finite), from
/// `scale² |a - p|²` against `|b - p|²` in integers: Algorithm 1's uniformity test where the
/// rounded lengths cannot tell (a ratio of exactly `u`, as on a grid).
#[inline(never)]
pub(crate) fn compare_scaled_distances(
    p: [f64; 2],
    a: [f64; 2],
    scale: f64,
    b: [f64; 2],
) -> Ordering {
    let Some((_, _, scale_exponent)) = decompose(scale) else {
        return if b == p {
            Ordering::Equal
        } else {
            Ordering::Less
        };
    };
    let bits = integer_bits(&[p, a, b]);
    // The squares' limbs, the scale's square (two mantissas), and the power of two moved to the
    // side that needs it, with a spare limb for the carries.
    let shift_limbs = (2 * scale_exponent.unsigned_abs() as usize).div_ceil(64) + 1;
    in_width!(
        2 * difference_limbs(bits) + 4 + shift_limbs,
        compare_scaled_distances_in(p, a, scale, scale_exponent, b)
    )
}

/// [`compare_scaled_distances`] in integers of `L` limbs, `e` the exponent of `scale`.
fn compare_scaled_distances_in<const L: usize>(
    p: [f64; 2],
    a: [f64; 2],
    scale: f64,
    e: i32,
    b: [f64; 2],
) -> Ordering {
    let [[px, py], a, b] = integers::<3, L>([p, a, b]);
    let squared = |[x, y]: [Int<L>; 2]| {
        let (dx, dy) = (x.sub(&px), y.sub(&py));
        dx.mul(&dx).add(&dy.mul(&dy))
    };
    // `e`: `scale`'s exponent, as the caller decomposed it (zero is answered there).
    // `scale = m · 2^e` with `m` odd: compare `m² A 2^2e` with `B`, the power of two on the side
    // where it is a whole number.
    let m = Int::<L>::from_f64(scale, e);
    let mut power = Int::<L>::ZERO;
    let shift = 2 * e.unsigned_abs() as usize;
    power.limbs[shift / 64] = 1 << (shift % 64);
    power.len = shift / 64 + 1;
    let (mut left, mut right) = (m.mul(&m).mul(&squared(a)), squared(b));
    if e >= 0 {
        left = left.mul(&power);
    } else {
        right = right.mul(&power);
    }
    left.sub(&right).signum()
}

/// [`compare_distances`] for coordinates of at most 62 bits in [`integers`]' unit: each difference
/// is under 2^63, its square under 2^126, a sum of two under 2^127, all in machine integers.
fn compare_distances_u128(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> Ordering {
    let e0 = least_exponent(&[p, a, b]);
    // `Int::from_f64` in machine integers.
    let integer = |c: f64| match decompose(c) {
        None => 0i128,
        Some((negative, mantissa, e)) => {
            let magnitude = i128::from(mantissa) << (e - e0);
            if negative {
                -magnitude
            } else {
                magnitude
            }
        }
    };
    let squared = |q: [f64; 2]| {
        let leg = |k: usize| (integer(q[k]) - integer(p[k])).unsigned_abs();
        let (dx, dy) = (leg(0), leg(1));
        dx * dx + dy * dy
    };
    squared(a).cmp(&squared(b))
}

/// [`compare_distances`] in integers of `L` limbs.
fn compare_distances_in<const L: usize>(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> Ordering {
    let [[px, py], a, b] = integers::<3, L>([p, a, b]);
    let squared = |[x, y]: [Int<L>; 2]| {
        let (dx, dy) = (x.sub(&px), y.sub(&py));
        dx.mul(&dx).add(&dy.mul(&dy))
    };
    squared(a).sub(&squared(b)).signum()
}

/// The limbs that a difference of two coordinates of `bits` bits ([`integer_bits`]) takes: one
/// bit more.
fn difference_limbs(bits: usize) -> usize {
    (bits + 1).div_ceil(64)
}

/// The most bits a coordinate of `points` takes as an integer in [`integers`]' unit.
fn integer_bits(points: &[[f64; 2]]) -> usize {
    let e0 = least_exponent(points);
    let parts = points.as_flattened().iter().filter_map(|&c| decompose(c));
    parts
        .map(|(_, mantissa, e)| (e - e0) as usize + (u64::BITS - mantissa.leading_zeros()) as usize)
        .max()
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(i: &Int) -> i128 {
        assert!(i.len <= 2);
        let m = i128::from(i.limbs[0]) | (i128::from(i.limbs[1]) << 64);
        if i.negative {
            -m
        } else {
            m
        }
    }

    #[test]
    fn small_integers_add_subtract_and_multiply_like_i128() {
        let mut rng = crate::test_rng::Xorshift::new(0x5851_f42d_4c95_7f2d);
        for _ in 0..10_000 {
            let mut draw = || (rng.next_u64() >> 12) as i64 - (1i64 << 51);
            let (x, y) = (draw() as f64, draw() as f64);
            let (a, b) = (Int::<LIMBS>::from_f64(x, 0), Int::<LIMBS>::from_f64(y, 0));
            let (xi, yi) = (x as i128, y as i128);
            assert_eq!(value(&a.add(&b)), xi + yi);
            assert_eq!(value(&a.sub(&b)), xi - yi);
            assert_eq!(value(&a.mul(&b)), xi * yi);
            assert_eq!(a.sub(&b).signum(), xi.cmp(&yi));
        }
    }

    #[test]
    fn dot_products_have_the_sign_of_their_integer_value() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        for _ in 0..5_000 {
            let mut draw = || ((rng.next_u64() >> 40) as i64 - (1i64 << 23)) as f64;
            let [a, b, c, d] = [
                [draw(), draw()],
                [draw(), draw()],
                [draw(), draw()],
                [draw(), draw()],
            ];
            let exact = (a[0] - b[0]) * (c[0] - d[0]) + (a[1] - b[1]) * (c[1] - d[1]);
            assert_eq!(dot_sign(a, b, c, d), exact.partial_cmp(&0.0).unwrap());
        }
        // Perpendicular, with magnitudes 2^2000 apart.
        let (big, tiny) = (2f64.powi(1000), 2f64.powi(-1000));
        assert_eq!(
            dot_sign([big, 0.0], [0.0, 0.0], [0.0, tiny], [0.0, 0.0]),
            Ordering::Equal
        );
        assert_eq!(
            dot_sign([big, tiny], [0.0, 0.0], [tiny, tiny], [0.0, 0.0]),
            Ordering::Greater
        );
    }

    #[test]
    fn doubles_decompose_into_odd_mantissas() {
        assert_eq!(decompose(0.0), None);
        assert_eq!(decompose(-0.0), None);
        assert_eq!(decompose(1.0), Some((false, 1, 0)));
        assert_eq!(decompose(-6.0), Some((true, 3, 1)));
        assert_eq!(decompose(f64::from_bits(1)), Some((false, 1, -1074)));
        assert_eq!(
            decompose(f64::MAX),
            Some((false, (1u64 << 53) - 1, 1023 - 52))
        );
    }

    #[test]
    fn carries_cross_limbs() {
        // 2^64 - 1 plus 1 is 2^64, then squared 2^128: three limbs, the lowest two zero.
        let all_ones =
            Int::<LIMBS>::from_f64(2f64.powi(64), 0).sub(&Int::<LIMBS>::from_f64(1.0, 0));
        assert_eq!(all_ones.len, 1);
        assert_eq!(all_ones.limbs[0], u64::MAX);
        let power = all_ones.add(&Int::<LIMBS>::from_f64(1.0, 0));
        assert_eq!((power.len, power.limbs[1]), (2, 1));
        let square = power.mul(&power);
        assert_eq!((square.len, square.limbs[2]), (3, 1));
        assert_eq!(square.sub(&square).signum(), Ordering::Equal);
    }

    #[test]
    fn the_widest_spread_fits() {
        let (tiny, huge) = (f64::from_bits(1), f64::MAX);
        let a = [huge, -huge];
        let b = [-huge, tiny];
        let c = [tiny, huge];
        // Three corners of a triangle spanning the whole double range, counter-clockwise.
        assert_eq!(
            orient2d_sign([-huge, -huge], [huge, -huge], c),
            Ordering::Greater
        );
        assert_eq!(orient2d_sign(a, b, c), Ordering::Less);
        assert_eq!(in_circle_sign(a, c, b, [tiny, -tiny]), Ordering::Greater);
        assert_eq!(in_circle_sign(a, c, b, [huge, huge]), Ordering::Less);
    }

    /// Two lengths whose rounded squares are equal (1.381966011250105, from a pentagon's
    /// `cos`/`sin` samples) are ordered exactly, the same after mirroring.
    #[test]
    fn distances_tied_when_rounded_are_ordered_exactly() {
        let p = [-1.0, 1.2246467991473532e-16];
        let a = [-0.30901699437494734, 0.9510565162951536];
        let b = [-0.30901699437494756, -0.9510565162951535];
        let squared = |q: [f64; 2]| (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]);
        assert_eq!(squared(a), squared(b));
        let order = compare_distances(p, a, b);
        assert_ne!(order, Ordering::Equal);
        let mirror = |q: [f64; 2]| [q[1], q[0]];
        assert_eq!(compare_distances(mirror(p), mirror(a), mirror(b)), order);
        assert_eq!(compare_distances(p, b, a), order.reverse());
        assert_eq!(compare_distances(p, a, a), Ordering::Equal);
    }

    /// Random points whose exponents lie within a window of `window` binary orders, a third of
    /// the time with ties built in (a mirror image, a point on a line through two others).
    fn spread_points(rng: &mut crate::test_rng::Xorshift, window: i32) -> [[f64; 2]; 4] {
        let mut draw = || {
            let mantissa = (rng.next_u64() >> 11) as f64 / 2f64.powi(53) + 0.5;
            let exponent = (rng.next_u64() % (window as u64 + 1)) as i32 - window / 2;
            let sign = if rng.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
            sign * libm::ldexp(mantissa, exponent)
        };
        let (p, a, c) = ([draw(), draw()], [draw(), draw()], [draw(), draw()]);
        let choice = draw().to_bits() % 3;
        let b = match choice {
            0 => [2.0 * p[0] - a[0], a[1]],
            1 => [a[0] + (a[0] - p[0]), a[1] + (a[1] - p[1])],
            _ => [draw(), draw()],
        };
        [p, a, b, c]
    }

    /// Each predicate in the narrow widths [`in_width`] picks gives the full width's sign, and
    /// the distances in machine integers too: exponent windows from 0 to 1,500 binary orders,
    /// which reach every width, ties included.
    #[test]
    fn narrow_and_full_width_signs_agree() {
        let mut rng = crate::test_rng::Xorshift::new(0x1405_7b7e_f767_814f);
        let (mut machine, mut widths) = (0, [0usize; 5]);
        for k in 0..12_000 {
            let window = (k % 301) * 5;
            let [p, a, b, c] = spread_points(&mut rng, window);
            let full = compare_distances_in::<LIMBS>(p, a, b);
            assert_eq!(compare_distances(p, a, b), full, "{p:?} {a:?} {b:?}");
            if integer_bits(&[p, a, b]) <= 62 {
                machine += 1;
                assert_eq!(compare_distances_u128(p, a, b), full, "{p:?} {a:?} {b:?}");
            }
            let full = orient2d_in::<LIMBS>(p, a, b);
            assert_eq!(orient2d_sign(p, a, b), full, "{p:?} {a:?} {b:?}");
            let full = dot_in::<LIMBS>(p, a, b, c);
            assert_eq!(dot_sign(p, a, b, c), full, "{p:?} {a:?} {b:?} {c:?}");
            let full = in_circle_in::<LIMBS>(p, a, b, c);
            assert_eq!(in_circle_sign(p, a, b, c), full, "{p:?} {a:?} {b:?} {c:?}");
            let limbs = 4 * difference_limbs(integer_bits(&[p, a, b, c])) + 4;
            widths[[8, 16, 32, 64].iter().take_while(|&&w| w < limbs).count()] += 1;
        }
        // Every width took part, in-circle's the widest.
        assert!(
            machine > 100 && widths.iter().all(|&w| w > 100),
            "{machine} {widths:?}"
        );
        // The machine integers' bound: 62 bits with the largest differences and squares.
        let top = libm::ldexp(1.0, 61) + 1.0;
        assert_eq!(integer_bits(&[[top, 1.0], [0.0, 0.0], [0.0, 0.0]]), 62);
        let (p, a, b) = ([top, -top], [-top, top], [top, top]);
        assert_eq!(compare_distances_u128(p, a, b), Ordering::Greater);
        assert_eq!(
            compare_distances_u128(p, a, [-top, -top + 2.0]),
            Ordering::Greater
        );
        assert_eq!(compare_distances_u128(p, b, [-top, -top]), Ordering::Equal);
        // On each side of every width's switch (a difference of 63 bits a limb; in-circle's
        // switches at 63, 191, 447, 959 and 1983 bits, the others' at 191, 447, 959, 1983) and at
        // the widest spread of doubles, with full mantissas: the largest differences.
        let switches = [63, 64, 191, 192, 447, 448, 959, 960, 1983, 1984, 2098];
        for bits in switches {
            let full = ((1u64 << 53) - 1) as f64;
            let (top, small) = (libm::ldexp(full, bits - 1127), f64::from_bits(1));
            let (p, a, b, c) = ([top, small], [-top, 0.0], [0.0, top], [-top, -top]);
            assert_eq!(integer_bits(&[p, a, b, c]), bits as usize);
            assert_eq!(orient2d_sign(p, a, b), orient2d_in::<LIMBS>(p, a, b));
            assert_eq!(
                in_circle_sign(p, a, b, c),
                in_circle_in::<LIMBS>(p, a, b, c)
            );
            assert_eq!(dot_sign(p, a, b, c), dot_in::<LIMBS>(p, a, b, c));
            assert_eq!(
                compare_distances(p, a, b),
                compare_distances_in::<LIMBS>(p, a, b)
            );
        }
    }
}
