//! The instruction set the engine's two hot loops (the force loop of a part and the kick) run with,
//! chosen per engine at run time: AVX-512 where the CPU has it, else AVX2, else the x86-64 baseline
//! (SSE2) the crate is built for. The scalar Rust code is compiled once per set; the pair loop runs on
//! lanes of four (AVX2) or eight (AVX-512) contacts (`lanes`), the kick on lanes of four with either.
//! Each lane does the same IEEE operation in the same order as the scalar code (Rust never fuses a
//! multiply and an add, and no contraction is enabled), so all three give the same bits:
//! `tests/bed_isa.rs` steps the shipped bed each way under every law family and compares the digests.
//!
//! Measured: with AVX2, 1323 -> 1101 instructions per particle-step on the shipped quarter bed,
//! `pasha_simplified`, before the lanes (`benches/engine_counts.sh`). AVX-512 lanes on this project's
//! AMD Zen 5 (full-width 512-bit units): docs/benchmarks.md "Issue 30, fourteenth round". An earlier
//! Intel Xeon ran compiler-widened AVX-512 code slower than AVX2 (its 512-bit clock); where that holds,
//! `POWDERFMU_ENGINE_ISA=avx2` keeps the four lanes.

/// An instruction set of the hot loops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    /// x86-64's baseline (SSE2), or any other target.
    Baseline,
    /// AVX2 (x86-64 only, where the CPU reports it).
    Avx2,
    /// AVX-512 F and DQ, with AVX2 (x86-64 only, where the CPU reports all three).
    Avx512,
}

impl Isa {
    /// The best this CPU offers, unless the environment variable `POWDERFMU_ENGINE_ISA` names a lower one
    /// (`baseline` or `avx2`: to compare, or to rule the choice out when chasing a problem).
    pub fn detect() -> Isa {
        let asked = std::env::var("POWDERFMU_ENGINE_ISA").ok().and_then(|v| Isa::from_name(&v));
        [Isa::Avx512, Isa::Avx2].into_iter().find(|&isa| isa.available() && asked.is_none_or(|a| isa.rank() <= a.rank())).unwrap_or(Isa::Baseline)
    }

    /// The set a name (`name`) spells, any case.
    pub fn from_name(name: &str) -> Option<Isa> {
        [Isa::Baseline, Isa::Avx2, Isa::Avx512].into_iter().find(|i| name.eq_ignore_ascii_case(i.name()))
    }

    fn rank(self) -> u8 {
        self as u8
    }

    /// Whether this CPU can run it.
    pub fn available(self) -> bool {
        match self {
            Isa::Baseline => true,
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => std::is_x86_feature_detected!("avx2"),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => {
                std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512dq")
            }
            #[cfg(not(target_arch = "x86_64"))]
            Isa::Avx2 | Isa::Avx512 => false,
        }
    }

    /// Its lower-case name, `baseline`, `avx2` or `avx512` (as `POWDERFMU_ENGINE_ISA` and reports spell it).
    pub fn name(self) -> &'static str {
        match self {
            Isa::Baseline => "baseline",
            Isa::Avx2 => "avx2",
            Isa::Avx512 => "avx512",
        }
    }
}
