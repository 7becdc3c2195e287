//! The engine's hot loops compiled for AVX2 and for AVX-512 (`bed/engine/isa.rs`), and the pair loop on
//! lanes of four (AVX2) or eight (AVX-512) where a law has one (`bed/engine/lanes`), step to the same bits
//! as the x86-64 baseline's scalar loops: every law of the table on the shipped quarter bed (one and two
//! threads), and indentations with the indenter and the die walls, with held spheres (the scalar loop)
//! and without (the lanes). `POWDERFMU_ENGINE_ISA` names the set (`baseline`, `avx2`; unset: the best
//! the CPU has); the bench prints the set it ran and a digest of every position, velocity and force. A set
//! this CPU lacks is left out of the comparison, with a line saying so.

use std::process::Command;

const BED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/beds/bed_004_ch6_quarter.pfbed");

/// The instruction sets compared: `(the value of POWDERFMU_ENGINE_ISA or None, the name the bench reports)`.
const SETS: [(Option<&str>, &str); 3] = [(Some("baseline"), "baseline"), (Some("avx2"), "avx2"), (None, "avx512")];

fn run(args: &[&str], isa: Option<&str>) -> String {
    let mut c = Command::new(env!("CARGO_BIN_EXE_powderfmu"));
    c.args(args);
    match isa {
        Some(isa) => c.env("POWDERFMU_ENGINE_ISA", isa),
        None => c.env_remove("POWDERFMU_ENGINE_ISA"),
    };
    let out = c.output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into()
}

fn field<'a>(out: &'a str, key: &str) -> &'a str {
    out.split_whitespace().find_map(|w| w.strip_prefix(key)).unwrap_or_else(|| panic!("no {key} in {out}"))
}

/// Whether this CPU runs a set (the bench's `isa=` names it).
fn available(name: &str) -> bool {
    #[cfg(target_arch = "x86_64")]
    return match name {
        "baseline" => true,
        "avx2" => std::is_x86_feature_detected!("avx2"),
        _ => std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512dq"),
    };
    #[cfg(not(target_arch = "x86_64"))]
    return name == "baseline";
}

/// The sets this CPU runs, after saying which it cannot.
fn sets() -> Vec<(Option<&'static str>, &'static str)> {
    for (_, name) in SETS.iter().filter(|(_, name)| !available(name)) {
        eprintln!("this CPU has no {name}: its loops are not compared here");
    }
    SETS.into_iter().filter(|(_, name)| available(name)).collect()
}

#[test]
fn every_law_steps_to_the_same_bits_with_avx512_avx2_and_the_baseline() {
    let laws = ["nan", "pasha", "pasha_simplified", "luding", "thornton_ning", "tomas", "hertz", "jkr", "jkr_modified", "hooke", "walton_braun"];
    for law in laws {
        for threads in ["1", "2"] {
            let args = ["bed", "bench", BED, "--model", law, "--steps", "40", "--warmup", "0", "--threads", threads];
            let runs: Vec<(&str, String)> = sets().into_iter().map(|(isa, name)| (name, run(&args, isa))).collect();
            let base = &runs[0].1;
            assert_eq!(field(base, "isa="), "baseline");
            assert_eq!(field(base, "pair_loop="), "scalar");
            // The scalar loop walks every slot and keeps no near list (`engine::near`).
            assert_eq!(field(base, "near_builds="), "0", "{law}, {threads} threads");
            assert_eq!(field(base, "near_mode="), "none", "{law}, {threads} threads");
            for (name, out) in &runs[1..] {
                assert_eq!(field(out, "isa="), *name);
                assert_eq!(field(out, "state_digest="), field(base, "state_digest="), "{law}, {threads} threads, {name}");
                // The lanes ran (so the comparison compared them): on lanes the laws that have them, the law
                // per lane for the others whose tangential damping has a fixed ratio to the normal one.
                let lanes = match law {
                    "pasha_simplified" | "hertz" | "hooke" | "jkr" | "jkr_modified" | "nan" => "vector",
                    "tomas" => "scalar",
                    _ => "per_lane",
                };
                assert_eq!(field(out, "pair_loop="), lanes, "{law}, {name}");
                // The lane loop ran over near lists, built at the first step and kept for most of the 40
                // (the quarter bed at rest moves far less than the shell in 40 steps).
                let near: u64 = field(out, "near_builds=").parse().unwrap();
                if lanes != "scalar" {
                    assert!((1..=4).contains(&near), "{law}, {threads} threads, {name}: {near} near list builds in 40 steps");
                    // The quarter's skin of 0.025 d leaves the near lists little to leave out: the lanes
                    // walk every slot (the skin test below runs the near lists).
                    assert_eq!(field(out, "near_mode="), "walk", "{law}, {threads} threads, {name}");
                }
            }
        }
    }
}

#[test]
fn an_indentation_is_the_same_with_avx512_avx2_and_the_baseline() {
    let dir = std::env::temp_dir().join(format!("powderfmu-isa-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // `fast` holds the spheres far from the indenter (the scalar pair loop); `full` moves every sphere (the
    // lanes, with contacts that slide and let go under the indenter).
    for fidelity in ["fast", "full"] {
        for threads in ["1", "2"] {
            let mut records = Vec::new();
            for (isa, name) in sets() {
                let out = dir.join(format!("{name}_{fidelity}_{threads}.csv"));
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
                run(&args, isa);
                records.push((name, std::fs::read(out).unwrap()));
            }
            let base = &records[0].1;
            assert!(base.len() > 200, "a force-depth record");
            for (name, record) in &records[1..] {
                assert!(record == base, "{fidelity}, {threads} threads: the force-depth records of {name} and the baseline differ");
            }
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
    let bench = |law: &str, skin: &str, forget: &str| -> (String, u64, u64, String) {
        let steps = if law == "pasha_simplified" { "2500" } else { "1000" };
        let args = [
            "bed",
            "bench",
            BED,
            "--model",
            law,
            "--steps",
            steps,
            "--warmup",
            "0",
            "--threads",
            "1",
            "--skin",
            skin,
            "--forgetting-distance",
            forget,
        ];
        let out = run(&args, None);
        let near = (field(&out, "near_builds=").parse().unwrap(), field(&out, "near_mode=").to_string());
        (field(&out, "state_digest=").to_string(), field(&out, "list_builds=").parse().unwrap(), near.0, near.1)
    };
    let mut rebuilt_more = 0;
    for law in laws {
        // Skins above and below the forgetting distance, run side by side: each run is one thread, and
        // run one after the other this test took 71 s of the suite (Thornton-Ning's 13 s each).
        let runs: Vec<_> = std::thread::scope(|s| {
            let spawned: Vec<_> = ["1e-4", "5e-6"].map(|skin| s.spawn(move || bench(law, skin, "2e-5"))).into();
            spawned.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert!(runs.iter().all(|r| r.0 == runs[0].0), "{law}: {runs:?}");
        rebuilt_more += usize::from(runs[1].1 > runs[0].1);
        // With the larger skin the lanes run over near lists (`engine::near`) that the moving spheres make
        // them rebuild several times: lists kept across steps and rebuilt give the same bits as a walk over
        // every slot (the smaller skin, whose lists keep nearly every slot, walks them).
        let (near, mode) = (runs[0].2, &runs[0].3);
        if !matches!(law, "tomas") {
            assert_eq!(mode, "near", "{law}: {runs:?}");
            assert!(near >= 3, "{law}: {near} near list builds");
        }
    }
    // The skin took effect: on most laws the smallest rebuilds more often (Nan's bed hardly moves).
    assert!(rebuilt_more >= laws.len() - 2, "{rebuilt_more} of {} laws rebuilt more often under the smallest skin", laws.len());
    // The forgetting distance does: in 2500 steps a Pasha pair separates by more than 2e-6 m and forgets
    // at that distance (tests/bed.rs holds one pair to the rule and the list to keeping it).
    let (forgetting, remembering) = std::thread::scope(|s| {
        let remembering = s.spawn(|| bench("pasha_simplified", "1e-4", "2e-5").0);
        (bench("pasha_simplified", "1e-4", "2e-6").0, remembering.join().unwrap())
    });
    assert_ne!(remembering, forgetting);
    // The lanes forget as the scalar loop does: the baseline steps to the same bits.
    let args = [
        "bed",
        "bench",
        BED,
        "--model",
        "pasha_simplified",
        "--steps",
        "2500",
        "--warmup",
        "0",
        "--threads",
        "1",
        "--skin",
        "1e-4",
        "--forgetting-distance",
        "2e-6",
    ];
    assert_eq!(field(&run(&args, Some("baseline")), "state_digest="), forgetting, "the baseline's scalar loop against the lanes");
    for (option, value) in [("--skin", "0"), ("--forgetting-distance", "0")] {
        let out = Command::new(env!("CARGO_BIN_EXE_powderfmu")).args(["bed", "bench", BED, "--model", "hertz", option, value]).output().unwrap();
        assert!(!out.status.success());
        assert!(String::from_utf8_lossy(&out.stderr).contains(option), "{}", String::from_utf8_lossy(&out.stderr));
    }
}
