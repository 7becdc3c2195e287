//! The instruction set the engine's two hot loops (the force loop of a part and the kick) run with,
//! chosen per engine at run time: AVX2 where the CPU has it, else the x86-64 baseline (SSE2) the crate
//! is built for. The same Rust code is compiled twice; LLVM packs the vector arithmetic of a contact into
//! 256-bit registers where it can. Each lane does the same IEEE operation in the same order as the
//! scalar code (Rust never fuses a multiply and an add, and no fused multiply-add is enabled), so both
//! give the same bits: `tests/bed.rs` steps the shipped bed both ways under every law family and compares
//! the digests.
//!
//! Measured on the shipped quarter bed, `pasha_simplified`, one thread (`benches/engine_counts.sh`):
//! 1323 instructions per particle-step with the baseline, 1101 with AVX2. AVX-512 was measured too and
//! left out: it ran slower on this machine's Xeon than AVX2 (medians of 5, 4.4e6 against 5.9e6
//! particle-steps/s), and Cachegrind cannot count it.

/// An instruction set of the hot loops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    /// x86-64's baseline (SSE2), or any other target.
    Baseline,
    /// AVX2 (x86-64 only, where the CPU reports it).
    Avx2,
}

impl Isa {
    /// The best this CPU offers, unless the environment variable `POWDERFMU_ENGINE_ISA` says
    /// `baseline` (to compare the two, or to rule the choice out when chasing a problem).
    pub fn detect() -> Isa {
        if std::env::var("POWDERFMU_ENGINE_ISA").is_ok_and(|v| v.eq_ignore_ascii_case("baseline")) {
            return Isa::Baseline;
        }
        if Isa::Avx2.available() {
            Isa::Avx2
        } else {
            Isa::Baseline
        }
    }

    /// Whether this CPU can run it.
    pub fn available(self) -> bool {
        match self {
            Isa::Baseline => true,
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => std::is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            Isa::Avx2 => false,
        }
    }

    /// Its lower-case name, `baseline` or `avx2` (as `POWDERFMU_ENGINE_ISA` and reports spell it).
    pub fn name(self) -> &'static str {
        match self {
            Isa::Baseline => "baseline",
            Isa::Avx2 => "avx2",
        }
    }
}
