//! The engine's hot loops compiled for AVX2 (`bed/engine/isa.rs`), and the pair loop on AVX2 lanes where
//! a law has one (`bed/engine/lanes`), step to the same bits as the x86-64 baseline's scalar loops: every
//! law of the table on the shipped quarter bed (one and two threads), and indentations with the
//! indenter and the die walls, with held spheres (the scalar loop) and without (the lanes). `POWDERFMU_ENGINE_ISA=baseline` forces the
//! baseline; the bench prints the ISA it ran and a digest of every position, velocity and force.

use std::process::Command;

const BED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/beds/bed_004_ch6_quarter.pfbed");

fn run(args: &[&str], baseline: bool) -> String {
    let mut c = Command::new(env!("CARGO_BIN_EXE_powderfmu"));
    c.args(args);
    if baseline {
        c.env("POWDERFMU_ENGINE_ISA", "baseline");
    } else {
        c.env_remove("POWDERFMU_ENGINE_ISA");
    }
    let out = c.output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into()
}

fn field<'a>(out: &'a str, key: &str) -> &'a str {
    out.split_whitespace().find_map(|w| w.strip_prefix(key)).unwrap_or_else(|| panic!("no {key} in {out}"))
}

/// Whether this CPU runs the AVX2 loops (then the comparisons below compare two builds of the loops).
fn avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

#[test]
fn every_law_steps_to_the_same_bits_with_avx2_and_the_baseline() {
    if !avx2() {
        eprintln!("this CPU has no AVX2: only the baseline loops run here, nothing to compare");
    }
    let laws = ["nan", "pasha", "pasha_simplified", "luding", "thornton_ning", "tomas", "hertz", "jkr", "jkr_modified", "hooke", "walton_braun"];
    for law in laws {
        for threads in ["1", "2"] {
            let args = ["bed", "bench", BED, "--model", law, "--steps", "40", "--warmup", "0", "--threads", threads];
            let (fast, base) = (run(&args, false), run(&args, true));
            assert_eq!(field(&base, "isa="), "baseline");
            assert_eq!(field(&fast, "isa="), if avx2() { "avx2" } else { "baseline" });
            assert_eq!(field(&fast, "state_digest="), field(&base, "state_digest="), "{law}, {threads} threads");
            assert_eq!(field(&base, "pair_loop="), "scalar");
            // The lanes ran (so the comparison compared them): on lanes the laws that have them, the law per
            // lane for the others whose tangential damping has a fixed ratio to the normal one.
            let lanes = match law {
                "pasha_simplified" | "hertz" | "hooke" | "jkr" | "jkr_modified" => "vector",
                "tomas" => "scalar",
                _ => "per_lane",
            };
            assert_eq!(field(&fast, "pair_loop="), if avx2() { lanes } else { "scalar" }, "{law}");
        }
    }
}

#[test]
fn an_indentation_is_the_same_with_avx2_and_the_baseline() {
    let dir = std::env::temp_dir().join(format!("powderfmu-isa-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // `fast` holds the spheres far from the indenter (the scalar pair loop); `full` moves every sphere (the
    // lanes, with contacts that slide and let go under the indenter).
    for fidelity in ["fast", "full"] {
        for threads in ["1", "2"] {
            let csv = |name: &str| dir.join(format!("{name}_{fidelity}_{threads}.csv"));
            for (name, baseline) in [("avx2", false), ("base", true)] {
                let out = csv(name);
                let args = [
                    "bed",
                    "indent",
                    BED,
                    "--speed",
                    "0.5",
                    "--max-penetration",
                    "1e-4",
                    "--every",
                    "2e-5",
                    "--fidelity",
                    fidelity,
                    "--threads",
                    threads,
                    "--out",
                    out.to_str().unwrap(),
                ];
                run(&args, baseline);
            }
            let (fast, base) = (std::fs::read(csv("avx2")).unwrap(), std::fs::read(csv("base")).unwrap());
            assert!(fast.len() > 200, "a force-depth record");
            assert!(fast == base, "{fidelity}, {threads} threads: the force-depth records differ");
        }
    }
}

#[test]
fn the_skin_changes_no_force_under_any_law() {
    // The skin decides which pairs the list holds, and so which of the lanes' blocks carry apart pairs; a
    // pair apart adds +0.0 to its bodies, and a contact forgets its memory beyond the forgetting distance
    // whatever the skin (a remembering pair beyond the skin stays in the list), so one thread steps to the
    // same bits under any skin above the reach, the plastic laws included. The bench's bed starts every
    // contact fresh, so the spheres move apart (the smaller skin rebuilds the list more often).
    let laws = ["nan", "pasha", "pasha_simplified", "luding", "thornton_ning", "tomas", "hertz", "jkr", "jkr_modified", "hooke", "walton_braun"];
    let bench = |law: &str, skin: &str, forget: &str| -> (String, u64) {
        let steps = if law == "pasha_simplified" { "2500" } else { "1000" };
        let args = ["bed", "bench", BED, "--model", law, "--steps", steps, "--warmup", "0", "--threads", "1", "--skin", skin, "--forgetting-distance", forget];
        let out = run(&args, false);
        (field(&out, "state_digest=").to_string(), field(&out, "list_builds=").parse().unwrap())
    };
    let mut rebuilt_more = 0;
    for law in laws {
        // Skins above and below the forgetting distance.
        let runs: Vec<(String, u64)> = ["1e-4", "5e-6"].iter().map(|skin| bench(law, skin, "2e-5")).collect();
        assert!(runs.iter().all(|r| r.0 == runs[0].0), "{law}: {runs:?}");
        rebuilt_more += usize::from(runs[1].1 > runs[0].1);
    }
    // The skin took effect: on most laws the smallest rebuilds more often (Nan's bed hardly moves).
    assert!(rebuilt_more >= laws.len() - 2, "{rebuilt_more} of {} laws rebuilt more often under the smallest skin", laws.len());
    // The forgetting distance does: in 2500 steps a Pasha pair separates by more than 2e-6 m and forgets
    // at that distance (tests/bed.rs holds one pair to the rule and the list to keeping it).
    let forgetting = bench("pasha_simplified", "1e-4", "2e-6").0;
    assert_ne!(bench("pasha_simplified", "1e-4", "2e-5").0, forgetting);
    // The lanes forget as the scalar loop does: the baseline steps to the same bits.
    let args = ["bed", "bench", BED, "--model", "pasha_simplified", "--steps", "2500", "--warmup", "0", "--threads", "1", "--skin", "1e-4", "--forgetting-distance", "2e-6"];
    assert_eq!(field(&run(&args, true), "state_digest="), forgetting, "the baseline's scalar loop against the lanes");
    for (option, value) in [("--skin", "0"), ("--forgetting-distance", "0")] {
        let out = Command::new(env!("CARGO_BIN_EXE_powderfmu")).args(["bed", "bench", BED, "--model", "hertz", option, value]).output().unwrap();
        assert!(!out.status.success());
        assert!(String::from_utf8_lossy(&out.stderr).contains(option), "{}", String::from_utf8_lossy(&out.stderr));
    }
}
