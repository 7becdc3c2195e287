//! Scenes from the seed papers' tables and the small soft beds, shared by the integration tests.
#![allow(dead_code)]

use powderfmu::bed::file::{self, BedFile};
use powderfmu::bed::{prepare, BedScene};
use powderfmu::scene::{ModelKind, Scene};

/// `count` soft spheres (E = 55 MPa, `jkr_friction_limit` pull_off, the bed scene's defaults otherwise) in
/// a die `die_diameter` [m] wide, consolidated to 10 kPa with interface energy `gamma` [J/m^2], as a bed
/// file read back from its bytes (what a unit loads): the compression and shear tests' beds.
pub fn soft_die_bed(gamma: f64, count: usize, die_diameter: f64) -> (BedFile, BedScene) {
    let scene = BedScene::from_json(&format!(
        r#"{{"particle_particle": {{"particle_youngs_modulus": 55e6, "surface_energy": {gamma}, "jkr_friction_limit": "pull_off"}}, "indenter_material": "wall", "particle_count": {count}, "die_diameter": {die_diameter}}}"#
    ))
    .unwrap();
    let (engine, _) = prepare::prepare(&scene, &mut |_| {}).unwrap();
    (file::decode(&file::encode(&engine.to_file(&scene).unwrap()).unwrap()).unwrap(), scene)
}

/// 000 Table 5: ammonium fluorescein on silicon, Gamma = 0.24 J/m^2 (docs/models.md's reading of "0.2 | 24").
pub fn table5(model: ModelKind, radius: f64, yield_pressure: f64) -> Scene {
    let mut s = Scene::new(model, radius, 1350.0, 1.2e9, 0.33);
    s.particle_yield_pressure = Some(yield_pressure);
    s.wall_youngs_modulus = Some(166e9);
    s.wall_poisson_ratio = 0.28;
    s.wall_yield_pressure = Some(120e6);
    s.surface_energy = 0.24;
    s
}

/// 000 Table 1, Ning column: E* = E/(1 - nu^2) against a much stiffer wall (000 Sec. 3.3).
pub fn table1_ning(model: ModelKind) -> Scene {
    let mut s = Scene::new(model, 2.45e-6, 1350.0, 1.2e9, 0.3);
    s.particle_yield_pressure = Some(35.3e6);
    s.surface_energy = 0.2;
    s
}

/// 000 Table 1, Du et al. column (density is not given; 12450 kg/m^3 of ruthenium only sets the mass).
pub fn table1_du(model: ModelKind) -> Scene {
    let mut s = Scene::new(model, 4e-6, 12450.0, 410e9, 0.3);
    s.particle_yield_pressure = Some(5.52e9);
    s.surface_energy = 1.0;
    s
}

/// 004 Table 4.1: ammonium fluorescein on silicon as Ning simulated it.
pub fn table4_1(model: ModelKind) -> Scene {
    let mut s = Scene::new(model, 2.45e-6, 1350.0, 1.2e9, 0.3);
    s.wall_youngs_modulus = Some(182e9);
    s.wall_poisson_ratio = 0.3;
    s.particle_yield_pressure = Some(35.3e6);
    s.surface_energy = 0.2;
    s
}

/// Gamma that makes 8/9 f_ce = 2.1 uN at R = 2.45 um (004 Table 4.2's f_01).
pub fn table4_2_surface_energy() -> f64 {
    2.1e-6 * 9.0 / 8.0 / (1.5 * std::f64::consts::PI * 2.45e-6)
}

/// 004 Table 4.2 on top of Table 4.1: k_e = 1500, k_p = 210, k_cp = k_c = 20 N/m, 8/9 f_ce = 2.1 uN, f_0p = 4.0 uN.
pub fn table4_2(model: ModelKind) -> Scene {
    let mut s = table4_1(model);
    s.surface_energy = table4_2_surface_energy();
    s.laws.stiffness.elastic_stiffness = Some(1500.0);
    s.laws.stiffness.plastic_stiffness = Some(210.0);
    s.laws.pasha_simplified.pasha_pull_off_stiffness = 20.0;
    s.laws.pasha_simplified.pasha_pull_off_intercept = Some(4.0e-6);
    s
}

pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}
