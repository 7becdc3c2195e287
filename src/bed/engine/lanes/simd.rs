//! The lanes' two widths behind one trait: `F64x4` (AVX2, four f64 in a 256-bit register) and `F64x8`
//! (AVX-512, eight in a 512-bit register), with their masks. The pair loop and the laws' lane evaluations
//! are written once against `Simd` and compiled for each width inside a function that enables its
//! instruction set (`lanes::pairs`), where every method here inlines to one or two instructions.
//!
//! Every method does per lane the IEEE operation the scalar code does (no fused multiply-add; `abs` and
//! `-x` touch the sign bit alone; a comparison is true where the scalar one is, NaN included), so either
//! width gives the scalar loop's bits (`tests/bed_isa.rs`).
//!
//! Why AVX-512: on this project's Zen 5 machine a contact-like chain of square roots, divisions and
//! products runs twice as fast on eight lanes as on four (2.5 against 1.27 ns per contact, medians of 5,
//! docs/benchmarks.md "Issue 30, fourteenth round").
//!
//! Safety: a value of these types is made only by the unsafe constructors (`splat`, `load`, ...), whose
//! contract is that the CPU runs the width's instruction set; the safe methods then rely on it.

use super::record::Record;
use crate::bed::engine::partition::Rows;
use crate::bed::Vec3;
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// A lane mask: all ones or all zeros per lane.
pub trait Mask: Copy + BitAnd<Output = Self> + BitOr<Output = Self> + Not<Output = Self> {
    /// Bit k set where lane k is true.
    fn bits(self) -> u32;
    /// Lanes where `self` is true and `other` is not.
    #[inline(always)]
    fn and_not(self, other: Self) -> Self {
        self & !other
    }
}

/// The spheres as the pair loop reads them: the engine's arrays (four lanes) or its records (eight lanes;
/// empty on an engine running four).
#[derive(Clone, Copy)]
pub struct Spheres<'a> {
    pub position: &'a [Vec3],
    pub velocity: &'a [Vec3],
    pub spin: &'a [Vec3],
    pub radius: &'a [f64],
    pub species: &'a [u16],
    pub records: &'a [Record],
}

/// A block's contacts' shares: per lane the force on the owner [N], the rolling load [N] and the
/// torques on owner and partner [N m] (the partner's force is the owner's negated).
#[derive(Clone, Copy)]
pub struct Share<V> {
    pub force: [V; 3],
    pub rolling: V,
    pub torque_i: [V; 3],
    pub torque_j: [V; 3],
}

/// Lanes of f64 of one width.
pub trait Simd: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self> {
    /// The number of lanes.
    const N: usize;
    type Mask: Mask;
    /// The lanes as an array (`[f64; N]`).
    type Array: Copy + Default + AsRef<[f64]> + AsMut<[f64]>;

    /// # Safety
    /// The CPU runs the width's instruction set (as for every constructor below).
    unsafe fn splat(x: f64) -> Self;
    /// The first N f64 of `x` (refused by a panic where it is shorter).
    unsafe fn load(x: &[f64]) -> Self;
    unsafe fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    unsafe fn mask_from_fn(f: impl FnMut(usize) -> bool) -> Self::Mask;

    fn to_array(self) -> Self::Array;
    fn sqrt(self) -> Self;
    /// The larger of the two; `other` where either is NaN or both are zeros (the x86 rule).
    fn max(self, other: Self) -> Self;
    /// The sign bit cleared.
    fn abs(self) -> Self;
    /// `self` where `m`, else +0.0.
    fn keep(self, m: Self::Mask) -> Self;
    /// +0.0 where `m`, else `self`.
    fn unless(self, m: Self::Mask) -> Self;
    /// `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// `<`, `<=`, `>`, `>=`, `==` (false where NaN), and `!(<=)`, `!(>=)`, `!=` (true where NaN).
    fn lt(self, o: Self) -> Self::Mask;
    fn le(self, o: Self) -> Self::Mask;
    fn gt(self, o: Self) -> Self::Mask;
    fn ge(self, o: Self) -> Self::Mask;
    fn eq(self, o: Self) -> Self::Mask;
    fn nle(self, o: Self) -> Self::Mask;
    fn nge(self, o: Self) -> Self::Mask;
    fn ne(self, o: Self) -> Self::Mask;
    /// Whether `gather_sphere` reads the records (else the arrays).
    const RECORDS: bool;
    /// Sphere `idx[k]` in lane k: x, y, z, r, vx, vy, vz, wx, wy, wz.
    ///
    /// # Safety
    /// As the constructors, and every `idx[k]` < the length of what is read (not checked here: the pair
    /// loop checks its indices once per block).
    unsafe fn gather_sphere(spheres: &Spheres, idx: &[usize]) -> [Self; 10];
    /// Adds each lane's share of a contact to its two bodies' records of eight f64 (`Load`, the part's
    /// from sphere `base` on): to `record[i[k] - base]` the row [force, rolling, torque_i, 0] of lane k,
    /// then to `record[j[k] - base]` the row [-force, rolling, torque_j, 0]; lane by lane in order
    /// k = 0, 1, ..., so each sum is the scalar loop's, added in its order. A sphere outside the records
    /// panics, as the scalar loop's index.
    ///
    /// # Safety
    /// As the constructors.
    unsafe fn add_shares(rows: &mut Rows, i: &[usize], j: &[usize], share: Share<Self>);
    /// Eight consecutive f64 from `rows[k]` on in lane k: the q-th of each row in the q-th result.
    ///
    /// # Safety
    /// As the constructors, and each `rows[k]` (k < N) points to eight readable f64.
    unsafe fn load_rows(rows: &[*const f64; 8]) -> [Self; 8];
    /// `load_rows` reversed for the lanes whose bit `mask` sets: lane k's values written to the eight f64
    /// from `rows[k]` on.
    ///
    /// # Safety
    /// As the constructors, and each `rows[k]` with its bit set points to eight writable f64.
    unsafe fn store_rows(rows: &[*mut f64; 8], q: &[Self; 8], mask: u32);
}

/// Lanes a, b, c, d to four rows [a_k, b_k, c_k, d_k].
#[inline(always)]
pub unsafe fn transpose(a: __m256d, b: __m256d, c: __m256d, d: __m256d) -> [__m256d; 4] {
    // SAFETY: AVX (the caller's).
    unsafe {
        let t0 = _mm256_unpacklo_pd(a, b);
        let t1 = _mm256_unpackhi_pd(a, b);
        let t2 = _mm256_unpacklo_pd(c, d);
        let t3 = _mm256_unpackhi_pd(c, d);
        [
            _mm256_permute2f128_pd(t0, t2, 0x20),
            _mm256_permute2f128_pd(t1, t3, 0x20),
            _mm256_permute2f128_pd(t0, t2, 0x31),
            _mm256_permute2f128_pd(t1, t3, 0x31),
        ]
    }
}

/// Four rows of four f64 as four lanes: row k's element c in lane k of the c-th (the kick's `Load` halves,
/// `F64x4::load_rows`).
///
/// # Safety
/// AVX, and each pointer holds four readable f64.
#[inline(always)]
pub unsafe fn load4x4(rows: [*const f64; 4]) -> [__m256d; 4] {
    // SAFETY: AVX and the rows (the caller's).
    unsafe { transpose(_mm256_loadu_pd(rows[0]), _mm256_loadu_pd(rows[1]), _mm256_loadu_pd(rows[2]), _mm256_loadu_pd(rows[3])) }
}

/// Eight lanes of eight quantities to one row per lane: row k is [q[0][k], q[1][k], ..., q[7][k]].
///
/// # Safety
/// AVX-512 F.
#[inline(always)]
unsafe fn transpose8(q: [__m512d; 8]) -> [__m512d; 8] {
    // SAFETY: AVX-512 F (the caller's).
    unsafe {
        // Pairs of quantities per lane: t[2p] holds (q[2p], q[2p+1]) of the even lanes, t[2p+1] of the odd.
        let t: [__m512d; 8] = [
            _mm512_unpacklo_pd(q[0], q[1]),
            _mm512_unpackhi_pd(q[0], q[1]),
            _mm512_unpacklo_pd(q[2], q[3]),
            _mm512_unpackhi_pd(q[2], q[3]),
            _mm512_unpacklo_pd(q[4], q[5]),
            _mm512_unpackhi_pd(q[4], q[5]),
            _mm512_unpacklo_pd(q[6], q[7]),
            _mm512_unpackhi_pd(q[6], q[7]),
        ];
        // Then 128-bit blocks: EVEN takes blocks 0 and 2 of each operand, ODD blocks 1 and 3; u[0] holds the
        // pairs of q[0..4] of lanes 0 and 4, u[1] of lanes 2 and 6, u[2] of 1 and 5, u[3] of 3 and 7; v the same of q[4..8].
        const EVEN: i32 = 0b10_00_10_00;
        const ODD: i32 = 0b11_01_11_01;
        let blocks = |even: __m512d, odd: __m512d, even2: __m512d, odd2: __m512d| {
            [
                _mm512_shuffle_f64x2::<EVEN>(even, even2),
                _mm512_shuffle_f64x2::<ODD>(even, even2),
                _mm512_shuffle_f64x2::<EVEN>(odd, odd2),
                _mm512_shuffle_f64x2::<ODD>(odd, odd2),
            ]
        };
        let (u, v) = (blocks(t[0], t[1], t[2], t[3]), blocks(t[4], t[5], t[6], t[7]));
        [
            _mm512_shuffle_f64x2::<EVEN>(u[0], v[0]),
            _mm512_shuffle_f64x2::<EVEN>(u[2], v[2]),
            _mm512_shuffle_f64x2::<EVEN>(u[1], v[1]),
            _mm512_shuffle_f64x2::<EVEN>(u[3], v[3]),
            _mm512_shuffle_f64x2::<ODD>(u[0], v[0]),
            _mm512_shuffle_f64x2::<ODD>(u[2], v[2]),
            _mm512_shuffle_f64x2::<ODD>(u[1], v[1]),
            _mm512_shuffle_f64x2::<ODD>(u[3], v[3]),
        ]
    }
}

/// Four 3-vectors as x, y and z lanes (masked loads: nothing read past the vector).
///
/// # Safety
/// AVX, and `idx[k] < v.len()` for k < 4 (the caller's check).
#[inline(always)]
unsafe fn gather3_256(v: &[Vec3], idx: &[usize]) -> [__m256d; 3] {
    // SAFETY: AVX and the indices (the caller's).
    unsafe {
        let three = _mm256_set_epi64x(0, -1, -1, -1);
        let row = |k: usize| _mm256_maskload_pd(v.get_unchecked(*idx.get_unchecked(k)).as_ptr(), three);
        let (r0, r1, r2, r3) = (row(0), row(1), row(2), row(3));
        let t0 = _mm256_unpacklo_pd(r0, r1); // x0 x1 z0 z1
        let t1 = _mm256_unpackhi_pd(r0, r1); // y0 y1 0 0
        let t2 = _mm256_unpacklo_pd(r2, r3);
        let t3 = _mm256_unpackhi_pd(r2, r3);
        [_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20), _mm256_permute2f128_pd(t0, t2, 0x31)]
    }
}

macro_rules! binary_ops {
    ($t:ident, $add:ident, $sub:ident, $mul:ident, $div:ident) => {
        impl Add for $t {
            type Output = $t;
            #[inline(always)]
            fn add(self, o: $t) -> $t {
                // SAFETY: a value of the type exists only where its instruction set runs (module docs).
                $t(unsafe { $add(self.0, o.0) })
            }
        }
        impl Sub for $t {
            type Output = $t;
            #[inline(always)]
            fn sub(self, o: $t) -> $t {
                // SAFETY: as above.
                $t(unsafe { $sub(self.0, o.0) })
            }
        }
        impl Mul for $t {
            type Output = $t;
            #[inline(always)]
            fn mul(self, o: $t) -> $t {
                // SAFETY: as above.
                $t(unsafe { $mul(self.0, o.0) })
            }
        }
        impl Div for $t {
            type Output = $t;
            #[inline(always)]
            fn div(self, o: $t) -> $t {
                // SAFETY: as above.
                $t(unsafe { $div(self.0, o.0) })
            }
        }
    };
}

/// Four f64 lanes (AVX2).
#[derive(Clone, Copy)]
pub struct F64x4(pub __m256d);

/// A mask of four lanes: all-ones or all-zeros f64 (as AVX2's comparisons give them).
#[derive(Clone, Copy)]
pub struct M4(__m256d);

binary_ops!(F64x4, _mm256_add_pd, _mm256_sub_pd, _mm256_mul_pd, _mm256_div_pd);

impl Neg for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn neg(self) -> F64x4 {
        // SAFETY: as above. Flipping the sign bit is the scalar `-x`.
        F64x4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
    }
}

impl BitAnd for M4 {
    type Output = M4;
    #[inline(always)]
    fn bitand(self, o: M4) -> M4 {
        // SAFETY: as above.
        M4(unsafe { _mm256_and_pd(self.0, o.0) })
    }
}

impl BitOr for M4 {
    type Output = M4;
    #[inline(always)]
    fn bitor(self, o: M4) -> M4 {
        // SAFETY: as above.
        M4(unsafe { _mm256_or_pd(self.0, o.0) })
    }
}

impl Not for M4 {
    type Output = M4;
    #[inline(always)]
    fn not(self) -> M4 {
        // SAFETY: as above.
        M4(unsafe { _mm256_xor_pd(self.0, _mm256_castsi256_pd(_mm256_set1_epi64x(-1))) })
    }
}

impl Mask for M4 {
    #[inline(always)]
    fn bits(self) -> u32 {
        // SAFETY: as above.
        unsafe { _mm256_movemask_pd(self.0) as u32 }
    }
    #[inline(always)]
    fn and_not(self, other: M4) -> M4 {
        // SAFETY: as above.
        M4(unsafe { _mm256_andnot_pd(other.0, self.0) })
    }
}

macro_rules! cmp4 {
    ($name:ident, $p:ident) => {
        #[inline(always)]
        fn $name(self, o: F64x4) -> M4 {
            // SAFETY: as above.
            M4(unsafe { _mm256_cmp_pd::<$p>(self.0, o.0) })
        }
    };
}

impl Simd for F64x4 {
    const N: usize = 4;
    type Mask = M4;
    type Array = [f64; 4];

    #[inline(always)]
    unsafe fn splat(x: f64) -> F64x4 {
        F64x4(unsafe { _mm256_set1_pd(x) })
    }
    #[inline(always)]
    unsafe fn load(x: &[f64]) -> F64x4 {
        F64x4(unsafe { _mm256_loadu_pd(x[..4].as_ptr()) })
    }
    #[inline(always)]
    unsafe fn from_fn(f: impl FnMut(usize) -> f64) -> F64x4 {
        let a: [f64; 4] = std::array::from_fn(f);
        unsafe { F64x4::load(&a) }
    }
    #[inline(always)]
    unsafe fn mask_from_fn(mut f: impl FnMut(usize) -> bool) -> M4 {
        let yes = f64::from_bits(u64::MAX);
        M4(unsafe { F64x4::from_fn(|k| if f(k) { yes } else { 0.0 }) }.0)
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        let mut a = [0.0; 4];
        // SAFETY: as above.
        unsafe { _mm256_storeu_pd(a.as_mut_ptr(), self.0) };
        a
    }
    #[inline(always)]
    fn sqrt(self) -> F64x4 {
        // SAFETY: as above.
        F64x4(unsafe { _mm256_sqrt_pd(self.0) })
    }
    #[inline(always)]
    fn max(self, o: F64x4) -> F64x4 {
        // SAFETY: as above.
        F64x4(unsafe { _mm256_max_pd(self.0, o.0) })
    }
    #[inline(always)]
    fn abs(self) -> F64x4 {
        // SAFETY: as above.
        F64x4(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
    }
    #[inline(always)]
    fn keep(self, m: M4) -> F64x4 {
        // SAFETY: as above.
        F64x4(unsafe { _mm256_and_pd(self.0, m.0) })
    }
    #[inline(always)]
    fn unless(self, m: M4) -> F64x4 {
        // SAFETY: as above.
        F64x4(unsafe { _mm256_andnot_pd(m.0, self.0) })
    }
    #[inline(always)]
    fn select(m: M4, a: F64x4, b: F64x4) -> F64x4 {
        // SAFETY: as above.
        F64x4(unsafe { _mm256_blendv_pd(b.0, a.0, m.0) })
    }
    cmp4!(lt, _CMP_LT_OQ);
    cmp4!(le, _CMP_LE_OQ);
    cmp4!(gt, _CMP_GT_OQ);
    cmp4!(ge, _CMP_GE_OQ);
    cmp4!(eq, _CMP_EQ_OQ);
    cmp4!(nle, _CMP_NLE_UQ);
    cmp4!(nge, _CMP_NGE_UQ);
    cmp4!(ne, _CMP_NEQ_UQ);
    // From the arrays: on four lanes the records ran 3-7 % slower than the arrays (the kick's writes
    // and two cache lines per sphere, against three 3-vector gathers; issue 30's seventeenth round).
    const RECORDS: bool = false;
    #[inline(always)]
    unsafe fn gather_sphere(spheres: &Spheres, idx: &[usize]) -> [F64x4; 10] {
        // SAFETY: AVX2 and the indices (the caller's).
        unsafe {
            let x = gather3_256(spheres.position, idx);
            let v = gather3_256(spheres.velocity, idx);
            let w = gather3_256(spheres.spin, idx);
            let r = F64x4::from_fn(|k| *spheres.radius.get_unchecked(*idx.get_unchecked(k)));
            let f = F64x4;
            [f(x[0]), f(x[1]), f(x[2]), r, f(v[0]), f(v[1]), f(v[2]), f(w[0]), f(w[1]), f(w[2])]
        }
    }
    #[inline(always)]
    unsafe fn load_rows(rows: &[*const f64; 8]) -> [F64x4; 8] {
        // SAFETY: AVX and the rows (the caller's).
        unsafe {
            // No closures around the loads: one would not take the caller's instruction set and would
            // call them out of line.
            let lo = load4x4([rows[0], rows[1], rows[2], rows[3]]);
            let hi = load4x4([rows[0].add(4), rows[1].add(4), rows[2].add(4), rows[3].add(4)]);
            let f = F64x4;
            [f(lo[0]), f(lo[1]), f(lo[2]), f(lo[3]), f(hi[0]), f(hi[1]), f(hi[2]), f(hi[3])]
        }
    }
    #[inline(always)]
    unsafe fn store_rows(rows: &[*mut f64; 8], q: &[F64x4; 8], mask: u32) {
        // SAFETY: AVX and the rows (the caller's).
        unsafe {
            let (lo, hi) = (transpose(q[0].0, q[1].0, q[2].0, q[3].0), transpose(q[4].0, q[5].0, q[6].0, q[7].0));
            for k in (0..4).filter(|k| mask & (1 << k) != 0) {
                _mm256_storeu_pd(rows[k], lo[k]);
                _mm256_storeu_pd(rows[k].add(4), hi[k]);
            }
        }
    }
    #[inline(always)]
    unsafe fn add_shares(rows: &mut Rows, i: &[usize], j: &[usize], share: Share<F64x4>) {
        let Share { force, rolling, torque_i, torque_j } = share;
        // SAFETY: AVX (the caller's); each record is eight f64.
        unsafe {
            let zero = _mm256_setzero_pd();
            let share = transpose(force[0].0, force[1].0, force[2].0, rolling.0);
            let ti = transpose(torque_i[0].0, torque_i[1].0, torque_i[2].0, zero);
            let tj = transpose(torque_j[0].0, torque_j[1].0, torque_j[2].0, zero);
            // The partner's force with its sign flipped (a - b is a + (-b) to the bit), the rolling load as is.
            let flip = _mm256_set_pd(0.0, -0.0, -0.0, -0.0);
            let add = |p: *mut f64, row: __m256d| _mm256_storeu_pd(p, _mm256_add_pd(_mm256_loadu_pd(p), row));
            for k in 0..4 {
                let a = rows.own(i[k]).as_mut_ptr();
                add(a, share[k]);
                add(a.add(4), ti[k]);
                let b = rows.at(j[k]).as_mut_ptr();
                add(b, _mm256_xor_pd(share[k], flip));
                add(b.add(4), tj[k]);
            }
        }
    }
}

/// Eight f64 lanes (AVX-512 F and DQ).
#[derive(Clone, Copy)]
pub struct F64x8(pub __m512d);

/// A mask of eight lanes: one bit per lane (AVX-512's mask registers).
#[derive(Clone, Copy)]
pub struct M8(__mmask8);

binary_ops!(F64x8, _mm512_add_pd, _mm512_sub_pd, _mm512_mul_pd, _mm512_div_pd);

impl Neg for F64x8 {
    type Output = F64x8;
    #[inline(always)]
    fn neg(self) -> F64x8 {
        // SAFETY: as above. Flipping the sign bit is the scalar `-x`.
        F64x8(unsafe { _mm512_xor_pd(self.0, _mm512_set1_pd(-0.0)) })
    }
}

impl BitAnd for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitand(self, o: M8) -> M8 {
        M8(self.0 & o.0)
    }
}

impl BitOr for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitor(self, o: M8) -> M8 {
        M8(self.0 | o.0)
    }
}

impl Not for M8 {
    type Output = M8;
    #[inline(always)]
    fn not(self) -> M8 {
        M8(!self.0)
    }
}

impl Mask for M8 {
    #[inline(always)]
    fn bits(self) -> u32 {
        self.0 as u32
    }
}

macro_rules! cmp8 {
    ($name:ident, $p:ident) => {
        #[inline(always)]
        fn $name(self, o: F64x8) -> M8 {
            // SAFETY: as above.
            M8(unsafe { _mm512_cmp_pd_mask::<$p>(self.0, o.0) })
        }
    };
}

impl Simd for F64x8 {
    const N: usize = 8;
    type Mask = M8;
    type Array = [f64; 8];

    #[inline(always)]
    unsafe fn splat(x: f64) -> F64x8 {
        F64x8(unsafe { _mm512_set1_pd(x) })
    }
    #[inline(always)]
    unsafe fn load(x: &[f64]) -> F64x8 {
        F64x8(unsafe { _mm512_loadu_pd(x[..8].as_ptr()) })
    }
    #[inline(always)]
    unsafe fn from_fn(f: impl FnMut(usize) -> f64) -> F64x8 {
        let a: [f64; 8] = std::array::from_fn(f);
        unsafe { F64x8::load(&a) }
    }
    #[inline(always)]
    unsafe fn mask_from_fn(mut f: impl FnMut(usize) -> bool) -> M8 {
        M8((0..8).fold(0u8, |m, k| if f(k) { m | 1 << k } else { m }))
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 8] {
        let mut a = [0.0; 8];
        // SAFETY: as above.
        unsafe { _mm512_storeu_pd(a.as_mut_ptr(), self.0) };
        a
    }
    #[inline(always)]
    fn sqrt(self) -> F64x8 {
        // SAFETY: as above.
        F64x8(unsafe { _mm512_sqrt_pd(self.0) })
    }
    #[inline(always)]
    fn max(self, o: F64x8) -> F64x8 {
        // SAFETY: as above.
        F64x8(unsafe { _mm512_max_pd(self.0, o.0) })
    }
    #[inline(always)]
    fn abs(self) -> F64x8 {
        // SAFETY: as above.
        F64x8(unsafe { _mm512_andnot_pd(_mm512_set1_pd(-0.0), self.0) })
    }
    #[inline(always)]
    fn keep(self, m: M8) -> F64x8 {
        // SAFETY: as above.
        F64x8(unsafe { _mm512_maskz_mov_pd(m.0, self.0) })
    }
    #[inline(always)]
    fn unless(self, m: M8) -> F64x8 {
        // SAFETY: as above.
        F64x8(unsafe { _mm512_maskz_mov_pd(!m.0, self.0) })
    }
    #[inline(always)]
    fn select(m: M8, a: F64x8, b: F64x8) -> F64x8 {
        // SAFETY: as above. The blend takes its second operand where the mask is set.
        F64x8(unsafe { _mm512_mask_blend_pd(m.0, b.0, a.0) })
    }
    cmp8!(lt, _CMP_LT_OQ);
    cmp8!(le, _CMP_LE_OQ);
    cmp8!(gt, _CMP_GT_OQ);
    cmp8!(ge, _CMP_GE_OQ);
    cmp8!(eq, _CMP_EQ_OQ);
    cmp8!(nle, _CMP_NLE_UQ);
    cmp8!(nge, _CMP_NGE_UQ);
    cmp8!(ne, _CMP_NEQ_UQ);
    // From the records: on eight lanes they made the linear spring 1.2 times as fast as two joined
    // four-lane gathers from the arrays (issue 30's seventeenth round).
    const RECORDS: bool = true;
    #[inline(always)]
    unsafe fn gather_sphere(spheres: &Spheres, idx: &[usize]) -> [F64x8; 10] {
        // SAFETY: AVX-512 F and the indices (the caller's).
        unsafe {
            let p = |k: usize| spheres.records.get_unchecked(*idx.get_unchecked(k)).0.as_ptr();
            let a = F64x8::load_rows(&[p(0), p(1), p(2), p(3), p(4), p(5), p(6), p(7)]);
            let lo = load4x4([p(0).add(8), p(1).add(8), p(2).add(8), p(3).add(8)]);
            let hi = load4x4([p(4).add(8), p(5).add(8), p(6).add(8), p(7).add(8)]);
            let join = |c: usize| _mm512_insertf64x4::<1>(_mm512_castpd256_pd512(lo[c]), hi[c]);
            let f = F64x8;
            // a[7] is the record's pad.
            [a[0], a[1], a[2], a[3], a[4], a[5], a[6], f(join(0)), f(join(1)), f(join(2))]
        }
    }
    #[inline(always)]
    unsafe fn load_rows(rows: &[*const f64; 8]) -> [F64x8; 8] {
        // SAFETY: AVX-512 F and the rows (the caller's).
        unsafe {
            let l = [
                _mm512_loadu_pd(rows[0]),
                _mm512_loadu_pd(rows[1]),
                _mm512_loadu_pd(rows[2]),
                _mm512_loadu_pd(rows[3]),
                _mm512_loadu_pd(rows[4]),
                _mm512_loadu_pd(rows[5]),
                _mm512_loadu_pd(rows[6]),
                _mm512_loadu_pd(rows[7]),
            ];
            let t = transpose8(l);
            [F64x8(t[0]), F64x8(t[1]), F64x8(t[2]), F64x8(t[3]), F64x8(t[4]), F64x8(t[5]), F64x8(t[6]), F64x8(t[7])]
        }
    }
    #[inline(always)]
    unsafe fn store_rows(rows: &[*mut f64; 8], q: &[F64x8; 8], mask: u32) {
        // SAFETY: AVX-512 F and the rows (the caller's); the transpose is its own inverse.
        unsafe {
            let r = transpose8([q[0].0, q[1].0, q[2].0, q[3].0, q[4].0, q[5].0, q[6].0, q[7].0]);
            for k in (0..8).filter(|k| mask & (1 << k) != 0) {
                _mm512_storeu_pd(rows[k], r[k]);
            }
        }
    }
    #[inline(always)]
    unsafe fn add_shares(rows: &mut Rows, i: &[usize], j: &[usize], share: Share<F64x8>) {
        let Share { force, rolling, torque_i, torque_j } = share;
        // SAFETY: AVX-512 F (the caller's); each record is eight f64.
        // One 512-bit add per body and lane, not two 256-bit ones (the record is one row of eight).
        unsafe {
            let zero = _mm512_setzero_pd();
            let minus = |x: F64x8| (-x).0;
            let ri = transpose8([force[0].0, force[1].0, force[2].0, rolling.0, torque_i[0].0, torque_i[1].0, torque_i[2].0, zero]);
            let rj = transpose8([minus(force[0]), minus(force[1]), minus(force[2]), rolling.0, torque_j[0].0, torque_j[1].0, torque_j[2].0, zero]);
            let add = |p: *mut f64, row: __m512d| _mm512_storeu_pd(p, _mm512_add_pd(_mm512_loadu_pd(p), row));
            for k in 0..8 {
                add(rows.own(i[k]).as_mut_ptr(), ri[k]);
                add(rows.at(j[k]).as_mut_ptr(), rj[k]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `gather_sphere` gives lane k sphere `idx[k]` (indices repeated and in any order), and `add_shares` adds to each body the scalar loop's rows, lane by lane in order, to the bit.
    #[inline(always)]
    unsafe fn check<V: Simd>() {
        // Sphere i's quantity q (x, y, z, r, vx, vy, vz, wx, wy, wz) is 100 i + q + 0.25, in the arrays and
        // the records (whose column 7 is a pad).
        let value = |i: usize, q: usize| (100 * i + q) as f64 + 0.25;
        let column = |q: usize| if q < 7 { q } else { q + 1 };
        let records: Vec<Record> =
            (0..20).map(|i| Record(std::array::from_fn(|c| (0..10).find(|&q| column(q) == c).map_or(0.0, |q| value(i, q))))).collect();
        let vec3 = |q: usize| (0..20).map(|i| Vec3::new(value(i, q), value(i, q + 1), value(i, q + 2))).collect::<Vec<_>>();
        let (position, velocity, spin) = (vec3(0), vec3(4), vec3(7));
        let radius: Vec<f64> = (0..20).map(|i| value(i, 3)).collect();
        let species = vec![0u16; 20];
        let spheres = Spheres { position: &position, velocity: &velocity, spin: &spin, radius: &radius, species: &species, records: &records };
        let idx = [3, 17, 3, 0, 19, 5, 5, 11];
        // SAFETY: the width's instruction set (the caller's), every index < 20.
        let lanes = unsafe { V::gather_sphere(&spheres, &idx[..V::N]) };
        for (q, lane) in lanes.iter().enumerate() {
            let a = lane.to_array();
            for k in 0..V::N {
                assert_eq!(a.as_ref()[k], value(idx[k], q), "lane {k}, quantity {q}");
            }
        }
        // Shares with sums that depend on the order of addition; bodies met by several lanes, as owner and partner.
        let (i, j) = ([0, 1, 1, 2, 0, 3, 4, 5], [1, 2, 0, 3, 3, 5, 5, 0]);
        let value = |q: usize, k: usize| (1.0 + 0.1 * k as f64) * [1.0e-3, 3.3, 0.7, 2.0e5, 1.1e-7, 9.0, 5.5, 1.0e-9, 0.3, 4.4][q];
        // SAFETY: the width's instruction set (the caller's).
        let lane = |q: usize| unsafe { V::from_fn(|k| value(q, k)) };
        let mut got = vec![[1.0f64; 8]; 6];
        let mut want = got.clone();
        // SAFETY: as above.
        unsafe {
            let share = Share {
                force: [lane(0), lane(1), lane(2)],
                rolling: lane(3),
                torque_i: [lane(4), lane(5), lane(6)],
                torque_j: [lane(7), lane(8), lane(9)],
            };
            V::add_shares(&mut Rows::new(0, &mut got, &mut []), &i[..V::N], &j[..V::N], share);
        }
        for k in 0..V::N {
            let v = |q: usize| value(q, k);
            let own = [v(0), v(1), v(2), v(3), v(4), v(5), v(6), 0.0];
            let partner = [-v(0), -v(1), -v(2), v(3), v(7), v(8), v(9), 0.0];
            for c in 0..8 {
                want[i[k]][c] += own[c];
            }
            for c in 0..8 {
                want[j[k]][c] += partner[c];
            }
        }
        for (b, (g, w)) in got.iter().zip(&want).enumerate() {
            assert_eq!(g.map(f64::to_bits), w.map(f64::to_bits), "body {b}: {g:?} against {w:?}");
        }
        // `load_rows` puts element q of row idx[k] in lane k of the q-th; `store_rows` writes lane k back
        // to its row where the mask says so, and no other row.
        let mut table: Vec<[f64; 8]> = (0..20).map(|r| std::array::from_fn(|q| (10 * r + q) as f64 + 0.5)).collect();
        let rows: [*const f64; 8] = std::array::from_fn(|k| table[idx[k]].as_ptr());
        // SAFETY: as above; every row holds eight f64.
        let q = unsafe { V::load_rows(&rows) };
        for (c, lane) in q.iter().enumerate() {
            for k in 0..V::N {
                assert_eq!(lane.to_array().as_ref()[k], table[idx[k]][c], "row lane {k}, element {c}");
            }
        }
        // Lanes 1, 3 and 4 (when there) stored with 1000 added, to rows 17, 0 and 19 (distinct).
        let mask = if V::N == 8 { 0b0001_1010 } else { 0b1010 };
        // SAFETY: as above.
        let shifted: [V; 8] = std::array::from_fn(|c| unsafe { V::from_fn(|k| table[idx[k]][c] + 1000.0) });
        let before = table.clone();
        let rows: [*mut f64; 8] = std::array::from_fn(|k| table[idx[k]].as_mut_ptr());
        // SAFETY: as above.
        unsafe { V::store_rows(&rows, &shifted, mask) };
        for (r, (now, was)) in table.iter().zip(&before).enumerate() {
            let stored = (0..V::N).any(|k| mask & (1 << k) != 0 && idx[k] == r);
            let want: [f64; 8] = std::array::from_fn(|c| was[c] + if stored { 1000.0 } else { 0.0 });
            assert_eq!(*now, want, "row {r} after store_rows");
        }
    }

    #[target_feature(enable = "avx2")]
    unsafe fn four() {
        // SAFETY: AVX2 (this function's).
        unsafe { check::<F64x4>() }
    }

    #[target_feature(enable = "avx2,avx512f,avx512dq")]
    unsafe fn eight() {
        // SAFETY: AVX-512 (this function's).
        unsafe { check::<F64x8>() }
    }

    #[test]
    fn records_gather_shares_add_and_rows_round_trip_at_both_widths() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("no AVX2 on this CPU: the lanes are not run");
            return;
        }
        // SAFETY: AVX2 checked.
        unsafe { four() };
        if !(std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512dq")) {
            eprintln!("no AVX-512 on this CPU: the eight lanes are not run");
            return;
        }
        // SAFETY: AVX-512 F and DQ checked.
        unsafe { eight() };
    }
}
