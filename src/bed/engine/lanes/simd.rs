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

/// Lanes of f64 of one width.
pub trait Simd: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self> {
    /// The number of lanes.
    const N: usize;
    type Mask: Mask;
    /// The lanes as an array (`[f64; N]`).
    type Array: Copy + Default + AsRef<[f64]> + AsMut<[f64]>;
    /// Per lane, a row of four f64 (a `Load` half): `[__m256d; N]`.
    type Rows: AsRef<[__m256d]>;

    /// # Safety
    /// The CPU runs the width's instruction set (as for every constructor below).
    unsafe fn splat(x: f64) -> Self;
    /// The first N f64 of `x` (refused by a panic where it is shorter).
    unsafe fn load(x: &[f64]) -> Self;
    unsafe fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    unsafe fn mask_from_fn(f: impl FnMut(usize) -> bool) -> Self::Mask;
    /// The x, y and z lanes of the 3-vectors `v[idx[k]]` (nothing read past a vector).
    ///
    /// # Safety
    /// As the constructors, and every `idx[k] < v.len()` (not checked here: the pair loop checks its
    /// indices once per block).
    unsafe fn gather3(v: &[Vec3], idx: &[usize]) -> [Self; 3];

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
    /// Lanes of four quantities to one row [a_k, b_k, c_k, d_k] per lane k.
    fn rows(a: Self, b: Self, c: Self, d: Self) -> Self::Rows;
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
    type Rows = [__m256d; 4];

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
    unsafe fn gather3(v: &[Vec3], idx: &[usize]) -> [F64x4; 3] {
        unsafe { gather3_256(v, idx).map(F64x4) }
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
    #[inline(always)]
    fn rows(a: F64x4, b: F64x4, c: F64x4, d: F64x4) -> [__m256d; 4] {
        // SAFETY: as above.
        unsafe { transpose(a.0, b.0, c.0, d.0) }
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
    type Rows = [__m256d; 8];

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
    unsafe fn gather3(v: &[Vec3], idx: &[usize]) -> [F64x8; 3] {
        // Two four-lane gathers joined: the hardware gather (three `vgatherqpd`) ran 15 % slower on the
        // linear bench (issue 30's fourteenth round).
        unsafe {
            let (lo, hi) = (gather3_256(v, &idx[..4]), gather3_256(v, &idx[4..8]));
            let join = |c: usize| F64x8(_mm512_insertf64x4::<1>(_mm512_castpd256_pd512(lo[c]), hi[c]));
            [join(0), join(1), join(2)]
        }
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
    #[inline(always)]
    fn rows(a: F64x8, b: F64x8, c: F64x8, d: F64x8) -> [__m256d; 8] {
        // SAFETY: as above.
        unsafe {
            let lo = |x: F64x8| _mm512_castpd512_pd256(x.0);
            let hi = |x: F64x8| _mm512_extractf64x4_pd::<1>(x.0);
            let l = transpose(lo(a), lo(b), lo(c), lo(d));
            let h = transpose(hi(a), hi(b), hi(c), hi(d));
            [l[0], l[1], l[2], l[3], h[0], h[1], h[2], h[3]]
        }
    }
}
