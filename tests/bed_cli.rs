//! `powderfmu bed ...` as a user runs it: prepare a small soft bed, read it back with every subcommand,
//! and bad input that must fail with a message, exit code 2 and no file written.

use std::path::PathBuf;
use std::process::Command;

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_powderfmu")).args(args).output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// A folder of this test's own (the tests run in parallel).
fn dir(test: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("powderfmu-bed-cli-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn prepare_then_info_snapshot_render_export_and_bench() {
    let d = dir("prepare");
    let scene = d.join("small.json");
    std::fs::write(&scene, r#"{"particle_particle": {"particle_youngs_modulus": 55e6}, "particle_count": 120, "die_diameter": 0.007}"#).unwrap();
    let bed = d.join("small.bed");
    // In two parts: settled, with a checkpoint at every progress report, then resumed to the end.
    let settled = d.join("settled.bed");
    let (code, out, err) =
        run(&["bed", "prepare", scene.to_str().unwrap(), "--until", "settle", "--checkpoint", "1e-6", "-o", settled.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("settle") && !out.contains("consolidate"), "{out}");
    assert!(!d.join("settled.checkpoint.pfbed").exists(), "the checkpoint goes once the bed is written");
    let (code, out, err) = run(&["bed", "prepare", "--resume", settled.to_str().unwrap(), "-o", bed.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("after phase `settle`"), "{err}");
    // Progress lines (not a terminal here) up to 100 %, and the consolidation report.
    assert!(err.contains("settle") && err.contains("100%"), "{err}");
    assert!(out.contains("consolidation stress reached") && out.contains("bed written to"), "{out}");
    let memory = |out: &str| out.lines().find(|l| l.starts_with("memory:")).map(str::to_string);
    let prepared = memory(&out);
    // The same settled fill branched to another consolidation stress; a bed consolidated already is refused.
    let other = d.join("other.bed");
    let (code, out2, err) =
        run(&["bed", "prepare", "--resume", settled.to_str().unwrap(), "--consolidation-stress", "5e3", "-o", other.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out2.contains("(target 5.0000e3 Pa)") && out.contains("(target 1.0000e4 Pa)"), "{out2}\n{out}");
    let (code, _, err) =
        run(&["bed", "prepare", "--resume", bed.to_str().unwrap(), "--consolidation-stress", "5e3", "-o", d.join("again.bed").to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("--consolidation-stress") && err.contains("consolidated (to 1e4 Pa) already"), "{err}");
    assert!(!d.join("again.bed").exists());
    let (code, _, err) = run(&["bed", "prepare", scene.to_str().unwrap(), "--consolidation-stress", "5e3"]);
    assert_eq!(code, 2, "--consolidation-stress needs --resume: {err}");
    let (code, _, err) = run(&["bed", "prepare", "--resume", settled.to_str().unwrap(), "--consolidation-stress", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--consolidation-stress") && err.contains("allowed"), "{err}");
    // A looser rest threshold for the phases still to run: the relax ends at the first check after its
    // minimum time (1 ms; checks every 2e-4 s or 50 steps).
    let relax = |out: &str| -> f64 { out.lines().find(|l| l.starts_with("relax")).unwrap().split_whitespace().nth(1).unwrap().parse().unwrap() };
    let loose = d.join("loose.bed");
    let (code, out3, err) =
        run(&["bed", "prepare", "--resume", settled.to_str().unwrap(), "--settle-energy-ratio", "0.9", "-o", loose.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        relax(&out3) < 1.5e-3 && relax(&out) > 2.0 * relax(&out3),
        "relax {} s with the ratio 0.9 against {} s with the scene's",
        relax(&out3),
        relax(&out)
    );
    for bad in ["0", "1", "2"] {
        let (code, _, err) =
            run(&["bed", "prepare", "--resume", settled.to_str().unwrap(), "--settle-energy-ratio", bad, "-o", d.join("bad.bed").to_str().unwrap()]);
        assert_eq!(code, 2, "--settle-energy-ratio {bad}: {err}");
        assert!(err.contains("--settle-energy-ratio") && err.contains("allowed"), "{err}");
    }
    assert!(!d.join("bad.bed").exists());
    let (code, out, err) = run(&["bed", "info", bed.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        prepared.is_some() && prepared == memory(&out),
        "bed prepare and bed info give one memory per particle: {prepared:?} vs {:?}",
        memory(&out)
    );
    for field in [
        "particles:            120",
        "bed height:",
        "solid fraction:",
        "coordination number:",
        "mean overlap:",
        "sigma_zz",
        "prepared through `unload`",
    ] {
        assert!(out.contains(field), "`{field}` missing in\n{out}");
    }
    let solid: f64 = out.lines().find(|l| l.starts_with("solid fraction")).unwrap().split_whitespace().last().unwrap().parse().unwrap();
    assert!(solid > 0.3 && solid < 0.74, "solid fraction {solid}");
    let vtk = d.join("small.vtk");
    assert_eq!(run(&["bed", "snapshot", bed.to_str().unwrap(), vtk.to_str().unwrap()]).0, 0);
    let text = std::fs::read_to_string(&vtk).unwrap();
    assert!(text.starts_with("# vtk DataFile") && text.contains("POINTS 120 double") && text.contains("SCALARS radius"));
    let csv = d.join("small.csv");
    assert_eq!(run(&["bed", "snapshot", bed.to_str().unwrap(), csv.to_str().unwrap()]).0, 0);
    assert_eq!(std::fs::read_to_string(&csv).unwrap().lines().count(), 121);
    let png = d.join("small.png");
    let (code, out, _) = run(&["bed", "render", bed.to_str().unwrap(), png.to_str().unwrap(), "--width", "200"]);
    assert_eq!(code, 0);
    assert!(out.contains("spheres cut"), "{out}");
    assert_eq!(&std::fs::read(&png).unwrap()[..8], b"\x89PNG\r\n\x1a\n");
    let data = d.join("small.data");
    assert_eq!(run(&["bed", "export-lammps", bed.to_str().unwrap(), data.to_str().unwrap()]).0, 0);
    let text = std::fs::read_to_string(&data).unwrap();
    assert!(text.contains("120 atoms") && text.contains("Atoms # sphere") && text.contains("Velocities"));
    let (code, out, err) = run(&["bed", "bench", bed.to_str().unwrap(), "--model", "hertz", "--steps", "50", "--warmup", "0"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("particle_steps_per_s=") && out.contains("bytes_per_particle="), "{out}");
    let curve = d.join("indent.csv");
    let indent = |fidelity: &str| {
        run(&[
            "bed",
            "indent",
            bed.to_str().unwrap(),
            "--diameter",
            "0.003",
            "--max-penetration",
            "0.0003",
            "--speed",
            "0.1",
            "--fidelity",
            fidelity,
            "--out",
            curve.to_str().unwrap(),
        ])
    };
    let (code, _, err) = indent("fast");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("hardness") && err.contains("spheres moving"), "{err}");
    let (code, _, err) = indent("medium");
    assert_eq!(code, 2);
    assert!(err.contains("--fidelity") && err.contains("fast, full"), "{err}");
    // The shear cell refuses a normal stress at or above the preshear's by name, and writes nothing.
    let sheared = d.join("shear.csv");
    let (code, _, err) = run(&["bed", "shear", bed.to_str().unwrap(), "--normal-fractions", "0.5,1.2", "--out", sheared.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("normal_stresses") && err.contains("preshear_stress"), "{err}");
    assert!(!sheared.exists());
    // ... and refuses it before the preshear, so no saved preshear is written either.
    let saved = d.join("preshear.pfshear");
    let (code, _, err) = run(&["bed", "shear", bed.to_str().unwrap(), "--normal-fractions", "0.5,1.2", "--save-preshear", saved.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(!saved.exists());
    let nowhere = d.join("no-such-folder").join("p.pfshear");
    let (code, _, err) = run(&["bed", "shear", bed.to_str().unwrap(), "--save-preshear", nowhere.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--save-preshear") && err.contains("does not exist"), "{err}");
    // A short test with its preshear saved, then the shears again from the saved preshear alone: the
    // same CSV to the byte (the state restores with its neighbour list as it was).
    let short = ["--preshear-travel", "0.5", "--shear-travel", "0.2", "--shear-speed", "0.02", "--normal-fractions", "0.3,0.6"];
    let (whole, again) = (d.join("whole.csv"), d.join("again.csv"));
    let mut args = vec!["bed", "shear", bed.to_str().unwrap(), "--save-preshear", saved.to_str().unwrap(), "--out", whole.to_str().unwrap()];
    args.extend(short);
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("preshear's end saved in") && saved.exists(), "{err}");
    let from = [
        "bed",
        "shear",
        "--from-preshear",
        saved.to_str().unwrap(),
        "--shear-travel",
        "0.2",
        "--shear-speed",
        "0.02",
        "--normal-fractions",
        "0.3,0.6",
    ];
    let mut args = from.to_vec();
    args.extend(["--out", again.to_str().unwrap()]);
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("the shears only") && err.contains("sigma_n"), "{err}");
    let (a, b) = (std::fs::read(&whole).unwrap(), std::fs::read(&again).unwrap());
    assert!(a.len() > 1000 && a == b, "the CSVs differ ({} and {} bytes)", a.len(), b.len());
    // The saved preshear fixes its stress; a bed file is not a saved preshear; a bed with a saved one is refused.
    let mut args = from.to_vec();
    args.extend(["--preshear-stress", "5000"]);
    let (code, _, err) = run(&args);
    assert_eq!(code, 2);
    assert!(err.contains("--preshear-stress") && err.contains("--from-preshear"), "{err}");
    let (code, _, err) = run(&["bed", "shear", "--from-preshear", bed.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("it is a bed file"), "{err}");
    let (code, _, err) = run(&["bed", "shear", bed.to_str().unwrap(), "--from-preshear", saved.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("--from-preshear"), "{err}");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bad_input_fails_by_name_and_writes_nothing() {
    let d = dir("bad");
    let scene = d.join("many.json");
    std::fs::write(&scene, r#"{"particle_count": 100000, "die_height": 0.02}"#).unwrap();
    let (code, _, err) = run(&["bed", "prepare", scene.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("insertion impossible") && err.contains("die_height"), "{err}");
    std::fs::write(&scene, r#"{"time_step": 1e-3}"#).unwrap();
    let (code, _, err) = run(&["bed", "prepare", scene.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("time_step") && err.contains("stability limit"), "{err}");
    let (code, _, err) = run(&["bed", "prepare", scene.to_str().unwrap(), "--until", "lunch"]);
    assert_eq!(code, 2);
    assert!(err.contains("--until") && err.contains("settle"), "{err}");
    let junk = d.join("junk.bed");
    std::fs::write(&junk, b"PFBED\0\0\0\x03\0\0\0\xff\xff\0\0\0\0\0\0").unwrap();
    let (code, _, err) = run(&["bed", "info", junk.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("truncated"), "{err}");
    // Only the two inputs are in the folder: nothing half-written.
    let mut names: Vec<String> = std::fs::read_dir(&d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, vec!["junk.bed".to_string(), "many.json".to_string()]);
    std::fs::remove_dir_all(&d).unwrap();
}

/// Every bed scene shipped in `scenes/` (beds, compression specimens, shear cells) loads and fills as its comment says: the sphere count, the
/// die, and (for the seed's Ch. 5 scenes) the glass beads' time step at E = 55 GPa, which the cost
/// estimates of docs/indentation.md are built on.
#[test]
fn every_shipped_bed_scene_fills() {
    let d = dir("scenes");
    let mut seen = 0;
    for entry in std::fs::read_dir("scenes").unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let bed_scene = ["bed_", "uct_", "shear_"].iter().any(|p| name.starts_with(p));
        if !(bed_scene && name.ends_with(".json")) {
            continue;
        }
        let scene: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let out_bed = d.join(name.replace(".json", ".pfbed"));
        let (code, out, err) = run(&["bed", "prepare", path.to_str().unwrap(), "--until", "fill", "-o", out_bed.to_str().unwrap()]);
        assert_eq!(code, 0, "{name}: {err}");
        assert!(out.contains("prepared through `fill`"), "{name}: {out}");
        let count = scene["particle_count"].as_u64().unwrap_or(16000);
        assert!(out.contains(&format!("particles:            {count}")), "{name}: {out}");
        let step: f64 = out.lines().find(|l| l.starts_with("time step:")).unwrap().split_whitespace().nth(2).unwrap().parse().unwrap();
        if name.starts_with("bed_004_ch5") || name.starts_with("bed_004_indentation") {
            // Table 5.2 as printed: the Rayleigh step of the 0.59 mm beads at 55 GPa.
            assert!((step - 6.75e-8).abs() < 0.01e-8, "{name}: time step {step:e} s");
        }
        seen += 1;
    }
    assert!(seen >= 22, "{seen} bed scenes found");
    std::fs::remove_dir_all(&d).unwrap();
}

/// `bed indent --change`: a one-change experiment on the same prepared bed. The bed's own value changes
/// nothing (to the byte of the force-depth CSV); another value changes the forces; a change of law, a
/// law too stiff for the bed's step, or text that is not a JSON object is refused by name, with exit 2.
#[test]
fn indent_change_lays_a_scene_over_the_same_bed() {
    let d = dir("change");
    let bed = "beds/bed_004_ch6_quarter.pfbed";
    let indent = |name: &str, change: Option<&str>| {
        let out = d.join(name);
        let mut args = vec![
            "bed",
            "indent",
            bed,
            "--speed",
            "0.5",
            "--max-penetration",
            "1e-4",
            "--every",
            "2e-5",
            "--fidelity",
            "fast",
            "--threads",
            "1",
            "--out",
            out.to_str().unwrap(),
        ];
        if let Some(c) = change {
            args.extend(["--change", c]);
        }
        let (code, _, err) = run(&args);
        (code, err, std::fs::read_to_string(&out).unwrap_or_default())
    };
    let (code, err, plain) = indent("plain.csv", None);
    assert_eq!(code, 0, "{err}");
    assert!(plain.lines().count() > 10, "{plain}");
    // Off a terminal the progress is a line per 5 %: loading, unloading, done, each with the time left.
    let progress: Vec<&str> = err.lines().filter(|l| l.contains("% ") && l.contains("left ~")).collect();
    assert!(progress.iter().any(|l| l.contains("loading") && l.contains("h/r")), "{err}");
    assert!(progress.last().is_some_and(|l| l.starts_with("100% done")), "{err}");
    // The loading is nearly the whole job, so the bar passes 80 % before the turn (it stopped at 50 % and
    // doubled the time left when the unloading counted as half).
    let last_loading = progress
        .iter()
        .filter_map(|l| l.split_once('%'))
        .filter(|(_, rest)| rest.trim_start().starts_with("loading"))
        .filter_map(|(percent, _)| percent.trim().parse::<f64>().ok())
        .fold(0.0, f64::max);
    assert!(last_loading >= 80.0, "the last loading line at {last_loading} %: {err}");
    // The shipped bed's rolling friction is 0.01 (scenes/bed_004_ch6_quarter.json).
    let (code, err, same) = indent("same.csv", Some(r#"{"rolling_friction": 0.01}"#));
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("scene changed by"), "{err}");
    assert_eq!(same, plain, "the bed's own value must change nothing");
    let (code, err, free) = indent("free.csv", Some(r#"{"rolling_friction": 0, "particle_particle": {"damping_factor_plastic": 0.1}}"#));
    assert_eq!(code, 0, "{err}");
    assert_ne!(free, plain, "no rolling friction and a tenth of the damping change the forces");
    for (change, name) in [
        (r#"{"particle_particle": {"contact_model": "hertz"}}"#, "contact_model"),
        (r#"{"particle_particle": {"elastic_stiffness": 1e9}}"#, "time_step"),
        (r#"{"rolling_friction": -1}"#, "rolling_friction"),
        ("[1]", "JSON object"),
    ] {
        let (code, err, _) = indent("refused.csv", Some(change));
        assert_eq!(code, 2, "{change}: {err}");
        assert!(err.contains("--change") && err.contains(name), "{change}: {err}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}
