//! The command-line tool as a user runs it: 000 Table 6 through `powderfmu analyze`, the help, and bad
//! input that must fail with a message naming the parameter and exit non-zero.

use powderfmu::analysis::OUTPUTS;
use powderfmu::scene::KEYS;
use serde_json::{json, Value};
use std::process::Command;

fn write_scene(name: &str, v: &Value) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("powderfmu-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_string_pretty(v).unwrap()).unwrap();
    path
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_powderfmu")).args(args).output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// 000 Table 5 (docs/models.md, "Reading the seeds": Gamma = 0.24 J/m^2, E* from particle and wall).
fn table5(radius: f64, p_y: f64) -> Value {
    json!({
        "contact_model": "nan",
        "particle_radius": radius, "particle_density": 1350.0,
        "particle_youngs_modulus": 1.2e9, "particle_poisson_ratio": 0.33, "particle_yield_pressure": p_y,
        "wall_youngs_modulus": 166e9, "wall_poisson_ratio": 0.28, "wall_yield_pressure": 120e6,
        "surface_energy": 0.24
    })
}

#[test]
fn table6_through_analyze_within_1_percent() {
    let radii = [3.445e-6, 2.45e-6, 1.72e-6, 1.29e-6];
    let v_s = [0.49, 0.66, 0.88, 1.12];
    for (p_y, v_ys) in [(25e6, [1.51, 2.25, 3.4, 4.76]), (30e6, [1.24, 1.86, 2.83, 3.96])] {
        for (i, r) in radii.iter().enumerate() {
            let path = write_scene(&format!("t6_{i}_{p_y}.json"), &table5(*r, p_y));
            let (code, out, err) = run(&["analyze", "--json", path.to_str().unwrap()]);
            assert_eq!(code, 0, "{err}");
            let v: Value = serde_json::from_str(&out).unwrap();
            let got_vs = v["jkr_sticking_velocity"].as_f64().unwrap();
            let got_vys = v["sticking_velocity"].as_f64().unwrap();
            assert!((got_vs / v_s[i] - 1.0).abs() < 0.011, "R {r}: V_s {got_vs} vs {}", v_s[i]);
            assert!((got_vys / v_ys[i] - 1.0).abs() < 0.01, "R {r}, p_y {p_y}: V_ys {got_vys} vs {}", v_ys[i]);
            assert_eq!(v["units"]["sticking_velocity"], "m/s");
        }
    }
}

#[test]
fn analyze_prints_every_required_key_with_its_unit() {
    let path = write_scene("keys.json", &table5(2.45e-6, 30e6));
    let (code, out, _) = run(&["analyze", "--json", path.to_str().unwrap(), "--velocity", "3"]);
    assert_eq!(code, 0);
    let v: Value = serde_json::from_str(&out).unwrap();
    for key in [
        "reduced_radius",
        "effective_modulus",
        "f_ce",
        "k_el",
        "k_cl",
        "k_p",
        "f_y",
        "alpha_y",
        "alpha_0",
        "jkr_sticking_velocity",
        "yield_velocity",
        "adhesive_yield_velocity",
        "sticking_velocity",
        "cohesion_yield_number",
        "rayleigh_time_step",
        "restitution",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
        assert!(v["units"].get(key).is_some() || v[key].is_null(), "no unit for {key}");
    }
    // 3 m/s is above V_ys = 1.86 m/s: the sphere rebounds.
    assert!(v["restitution"].as_f64().unwrap() > 0.0);
}

#[test]
fn help_lists_every_scene_key_and_output_with_units() {
    let (code, out, _) = run(&["analyze", "--help"]);
    assert_eq!(code, 0);
    for k in KEYS.iter() {
        assert!(out.contains(k.name) && out.contains(&format!("[{}]", k.unit)), "help misses {}", k.name);
    }
    for o in OUTPUTS {
        assert!(out.contains(o.name), "help misses output {}", o.name);
    }
}

fn expect_error(name: &str, scene: Value, must_contain: &[&str]) {
    let path = write_scene(name, &scene);
    let (code, out, err) = run(&["analyze", path.to_str().unwrap()]);
    assert_ne!(code, 0, "{name} should fail");
    assert!(out.is_empty(), "{name}: nothing on stdout on error");
    for text in must_contain {
        assert!(err.contains(text), "{name}: `{text}` not in: {err}");
    }
}

#[test]
fn bad_input_fails_naming_the_parameter_and_its_range() {
    let base = table5(2.45e-6, 30e6);
    let with = |k: &str, v: Value| {
        let mut s = base.clone();
        s[k] = v;
        s
    };
    expect_error("neg_radius.json", with("particle_radius", json!(-1e-6)), &["particle_radius", "[1e-9, 1) m"]);
    expect_error("zero_radius.json", with("particle_radius", json!(0.0)), &["particle_radius", "[1e-9, 1) m"]);
    expect_error("zero_modulus.json", with("particle_youngs_modulus", json!(0.0)), &["particle_youngs_modulus", "[1000, 1e13) Pa"]);
    expect_error("light.json", with("particle_density", json!(1e-100)), &["particle_density", "[1, 100000) kg/m^3"]);
    expect_error("neg_density.json", with("particle_density", json!(-1350.0)), &["particle_density", "kg/m^3"]);
    expect_error("nu_half.json", with("particle_poisson_ratio", json!(0.5)), &["particle_poisson_ratio", "(-1, 0.5)"]);
    expect_error("nu_minus1.json", with("particle_poisson_ratio", json!(-1.0)), &["particle_poisson_ratio", "(-1, 0.5)"]);
    expect_error("kp_too_big.json", with("plastic_stiffness", json!(1e6)), &["plastic_stiffness", "exceeds k_el"]);
    expect_error("gamma_kcl.json", with("surface_energy", json!(50.0)), &["surface_energy", "k_cl negative", "J/m^2"]);
    expect_error("model.json", with("contact_model", json!("hookean")), &["contact_model", "hookean", "nan, pasha"]);
    expect_error("typo.json", with("surface_enrgy", json!(0.1)), &["surface_enrgy", "did you mean `surface_energy`"]);
    expect_error("string.json", with("particle_radius", json!("2.45e-6")), &["particle_radius", "must be a number"]);
    let mut missing = base.clone();
    missing.as_object_mut().unwrap().remove("particle_density");
    expect_error("missing.json", missing, &["particle_density", "required"]);
    let mut no_py = base.clone();
    no_py.as_object_mut().unwrap().remove("particle_yield_pressure");
    no_py.as_object_mut().unwrap().remove("wall_yield_pressure");
    expect_error("no_py.json", no_py, &["particle_yield_pressure", "contact_model nan"]);
}

#[test]
fn unreadable_or_malformed_scenes_fail_cleanly() {
    let (code, _, err) = run(&["analyze", "/nonexistent/scene.json"]);
    assert_ne!(code, 0);
    assert!(err.contains("cannot read scene"));
    let dir = std::env::temp_dir().join(format!("powderfmu-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("broken.json");
    std::fs::write(&p, "{ not json").unwrap();
    let (code, _, err) = run(&["analyze", p.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("not valid JSON"), "{err}");
    let (code, _, err) = run(&["analyze", p.to_str().unwrap(), "--velocity", "-2"]);
    assert_ne!(code, 0);
    assert!(err.contains("--velocity"));
    let (code, _, _) = run(&["frobnicate"]);
    assert_ne!(code, 0);
}

#[test]
fn restitution_curve_finds_the_analyzed_sticking_velocity() {
    let path = write_scene("rest.json", &table5(2.45e-6, 30e6));
    let p = path.to_str().unwrap();
    let (code, out, err) = run(&["restitution", p, "--velocities", "0.5,1,1.5,2,4,8"]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].starts_with("impact_velocity_m_per_s,rebound_velocity_m_per_s,restitution"));
    assert_eq!(lines.len(), 1 + 6 + 1);
    let v_energy: f64 = lines[7].split('=').nth(1).unwrap().trim().parse().unwrap();
    let (_, json_out, _) = run(&["analyze", "--json", p]);
    let v: Value = serde_json::from_str(&json_out).unwrap();
    let v_theory = v["sticking_velocity"].as_f64().unwrap();
    // Two independent routes: the closed form of 000 Eqs. 78-79 and the integral of the law's force.
    assert!((v_energy / v_theory - 1.0).abs() < 1e-8, "{v_energy} vs {v_theory}");
}

#[test]
fn curve_walks_load_unload_and_detachment() {
    let path = write_scene("curve.json", &table5(2.45e-6, 30e6));
    let (code, out, err) = run(&["curve", path.to_str().unwrap(), "--path", "5e-8,-2e-8", "--points", "400"]);
    assert_eq!(code, 0, "{err}");
    let branches: Vec<&str> = out.lines().skip(1).map(|l| l.split(',').nth(3).unwrap()).collect();
    assert_eq!(branches.len(), 800);
    for b in ["Separated", "Plastic", "Elastic", "Adhesive"] {
        assert!(branches.contains(&b), "no {b} state on the path");
    }
    let (code, _, err) = run(&["curve", path.to_str().unwrap(), "--path", "1e-8,abc"]);
    assert_ne!(code, 0);
    assert!(err.contains("--path"));
}

fn analyze(name: &str, scene: &Value) -> Value {
    let path = write_scene(name, scene);
    let (code, out, err) = run(&["analyze", "--json", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

fn restitution_sticking_velocity(name: &str, scene: &Value, velocities: &str) -> f64 {
    let path = write_scene(name, scene);
    let (code, out, err) = run(&["restitution", path.to_str().unwrap(), "--velocities", velocities]);
    assert_eq!(code, 0, "{err}");
    out.lines().find_map(|l| l.strip_prefix("# sticking_velocity_m_per_s = ")).expect("no sticking velocity in the bracket").trim().parse().unwrap()
}

#[test]
fn sticking_velocity_is_the_active_laws_and_the_nan_value_says_so_by_name() {
    // 004 Table 4.2 (simplified Pasha law): analyze used to print the Nan law's 252.8 m/s here.
    let scene: Value = serde_json::from_str(&std::fs::read_to_string("scenes/pasha_table_4_2.json").unwrap()).unwrap();
    let v = analyze("pasha42.json", &scene);
    let active = v["sticking_velocity"].as_f64().unwrap();
    let by_restitution = restitution_sticking_velocity("pasha42r.json", &scene, "1.0,2.0");
    assert!((active / by_restitution - 1.0).abs() < 1e-8, "{active} vs restitution's {by_restitution}");
    assert!((active - 1.50).abs() < 0.01, "004 Table 4.2 sticks below ~1.5 m/s: {active}");
    assert!(v["nan_sticking_velocity"].as_f64().unwrap() > 100.0);
    assert_eq!(v["units"]["nan_sticking_velocity"], "m/s");
    // For the Nan law both are the closed form.
    let v = analyze("nan_both.json", &table5(2.45e-6, 30e6));
    assert_eq!(v["sticking_velocity"], v["nan_sticking_velocity"]);
    // A law without adhesion never sticks.
    let mut hertz = table5(2.45e-6, 30e6);
    hertz["contact_model"] = json!("hertz");
    hertz["surface_energy"] = json!(0.0);
    assert_eq!(analyze("hertz.json", &hertz)["sticking_velocity"], json!(0.0));
}

#[test]
fn jkr_quantities_need_no_yield_pressure() {
    let mut scene = table5(2.45e-6, 30e6);
    let with_yield = analyze("jkr_py.json", &scene);
    let obj = scene.as_object_mut().unwrap();
    obj.remove("particle_yield_pressure");
    obj.remove("wall_yield_pressure");
    obj.insert("contact_model".into(), json!("jkr"));
    let v = analyze("jkr_no_py.json", &scene);
    for key in ["w_jkr", "jkr_sticking_velocity"] {
        assert_eq!(v[key], with_yield[key], "{key}");
        assert!(v["units"][key].is_string(), "{key} has a unit");
    }
    // 000 Table 6: V_s = 0.66 m/s at R = 2.45 um; the JKR law's own energy balance (detachment at
    // -5/9 F_c, 000 App. B) gives the same W_0 = W_JKR.
    let v_s = v["jkr_sticking_velocity"].as_f64().unwrap();
    assert!((v_s / 0.66 - 1.0).abs() < 0.01, "{v_s}");
    let active = v["sticking_velocity"].as_f64().unwrap();
    assert!((active / v_s - 1.0).abs() < 1e-3, "{active} vs {v_s}");
    let notes = v["notes"].as_array().cloned().unwrap_or_default();
    assert!(!notes.iter().any(|n| n.as_str().unwrap().contains("jkr_detachment")), "{notes:?}");
}

/// With `jkr_detachment = force` the active sticking velocity is the force reading's (0.703 of Eq. 73's)
/// and the output says which reading each value is.
#[test]
fn jkr_sticking_velocities_name_their_reading() {
    let mut scene = table5(2.45e-6, 30e6);
    let obj = scene.as_object_mut().unwrap();
    obj.insert("contact_model".into(), json!("jkr"));
    obj.insert("jkr_detachment".into(), json!("force"));
    let v = analyze("jkr_force.json", &scene);
    let (active, eq73) = (v["sticking_velocity"].as_f64().unwrap(), v["jkr_sticking_velocity"].as_f64().unwrap());
    assert!((active / eq73 - 0.703).abs() < 1e-3, "{active} / {eq73}");
    let notes: Vec<&str> = v["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap()).collect();
    assert!(notes.iter().any(|n| n.contains("sticking_velocity is jkr_detachment = force's") && n.contains("displacement reading")), "{notes:?}");
}

#[test]
#[cfg(unix)]
fn a_closed_pipe_ends_the_tool_quietly() {
    use std::process::Stdio;
    // `powderfmu analyze --help | head -1`: the reader goes away after the first line.
    let mut child =
        Command::new(env!("CARGO_BIN_EXE_powderfmu")).args(["analyze", "--help"]).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(0), "the tool exits 0 when its reader has gone: {:?}", out.status);
}

#[test]
fn every_subcommand_has_help_and_errors_name_the_option() {
    for args in [
        &["--help"][..],
        &["analyze", "--help"],
        &["curve", "--help"],
        &["restitution", "--help"],
        &["completions", "--help"],
        &["bed", "--help"],
        &["bed", "prepare", "--help"],
        &["bed", "info", "--help"],
        &["bed", "snapshot", "--help"],
        &["bed", "render", "--help"],
        &["bed", "export-lammps", "--help"],
        &["bed", "indent", "--help"],
        &["bed", "bench", "--help"],
        &["bed", "compress", "--help"],
        &["bed", "shear", "--help"],
    ] {
        let (code, out, err) = run(args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(out.contains("Usage: powderfmu"), "{args:?}: {out}");
    }
    let (code, _, err) = run(&["curve", "x.json", "--path", "1e-6", "--points", "1"]);
    assert_eq!(code, 2);
    assert!(err.contains("--points") && err.contains("2..=1000000"), "{err}");
    let (code, _, err) = run(&["bed", "compress", "x.bed", "--strain-rate", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--strain-rate"), "{err}");
    let (code, _, err) = run(&["bed", "shear", "x.bed", "--split", "0.95"]);
    assert_eq!(code, 2);
    assert!(err.contains("--split") && err.contains("0.1"), "{err}");
    let (code, _, err) = run(&["bed", "render", "x.bed", "y.png", "--width", "wide"]);
    assert_eq!(code, 2);
    assert!(err.contains("--width"), "{err}");
    let (code, _, err) = run(&["restitution", "x.json", "--velocitys", "1"]);
    assert_eq!(code, 2);
    assert!(err.contains("--velocitys") && err.contains("--velocities"), "a misspelt option is named with the right one: {err}");
}

#[test]
fn shell_completions_cover_the_subcommands() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let (code, out, err) = run(&["completions", shell]);
        assert_eq!(code, 0, "{shell}: {err}");
        assert!(out.contains("restitution") && out.contains("export-lammps"), "{shell}");
    }
    let (code, _, _) = run(&["completions", "tcsh"]);
    assert_eq!(code, 2);
}

#[test]
fn curve_starts_where_asked() {
    let scene = write_scene("curve_start.json", &table5(2.45e-6, 30e6));
    let (code, out, err) = run(&["curve", scene.to_str().unwrap(), "--path", "2e-9", "--start", "-1e-9", "--points", "3"]);
    assert_eq!(code, 0, "{err}");
    let overlaps: Vec<f64> = out.lines().skip(1).map(|l| l.split(',').next().unwrap().parse().unwrap()).collect();
    assert_eq!(overlaps.len(), 3);
    for (got, want) in overlaps.iter().zip([0.0, 1e-9, 2e-9]) {
        assert!((got - want).abs() < 1e-21, "{overlaps:?}");
    }
    let (_, out, _) = run(&["curve", scene.to_str().unwrap(), "--path", "2e-9", "--points", "2"]);
    let first: f64 = out.lines().nth(1).unwrap().split(',').next().unwrap().parse().unwrap();
    assert_eq!(first, 0.0, "by default the path starts at -2e-9 and its first state is halfway, at 0");
}

#[test]
fn analyze_text_puts_each_unit_beside_its_value_under_its_law() {
    let path = write_scene("text.json", &table5(2.45e-6, 30e6));
    let (code, out, err) = run(&["analyze", path.to_str().unwrap(), "--velocity", "3"]);
    assert_eq!(code, 0, "{err}");
    let (_, json_out, _) = run(&["analyze", "--json", path.to_str().unwrap(), "--velocity", "3"]);
    let v: Value = serde_json::from_str(&json_out).unwrap();
    for o in OUTPUTS {
        let Some(value) = v.get(o.name) else { continue };
        let line = out.lines().find(|l| l.split_whitespace().next() == Some(o.name)).unwrap_or_else(|| panic!("no line for {}:\n{out}", o.name));
        if let Some(x) = value.as_f64() {
            let mut words = line.split_whitespace().skip(1);
            let shown: f64 = words.next().unwrap().parse().unwrap();
            assert!((shown - x).abs() <= 1e-5 * x.abs(), "{line}: {x}");
            if o.unit != "-" {
                assert_eq!(words.next(), Some(o.unit), "{line}");
            }
        }
    }
    // Sections by law: the Nan quantities under Nan's, V_s under JKR, the restitution under the impact.
    let section = |key: &str| {
        let at = out.find(&format!("  {key} ")).unwrap();
        out[..at].lines().rfind(|l| !l.starts_with(' ') && !l.is_empty()).unwrap().to_string()
    };
    assert!(section("k_el").starts_with("Nan's law"), "{}", section("k_el"));
    assert!(section("jkr_sticking_velocity").starts_with("JKR"));
    assert!(section("sticking_velocity").starts_with("the active law, nan"));
    assert!(section("restitution").starts_with("one undamped impact of nan"));
}
