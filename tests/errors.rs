//! Bad input gives a typed error that names the parameter, for every law's own keys too.

use powderfmu::law::pasha::PashaStiffnessLaw;
use powderfmu::law::AnyLaw;
use powderfmu::scene::{ModelKind, Scene};
use powderfmu::ParamError;

fn base(model: ModelKind) -> Scene {
    let mut s = Scene::new(model, 2.45e-6, 1350.0, 1.2e9, 0.3);
    s.particle_yield_pressure = Some(35e6);
    s.surface_energy = 0.2;
    s
}

fn names(s: &Scene, parameter: &str) {
    match AnyLaw::from_scene(s) {
        Ok(_) => panic!("{:?}: expected an error on {parameter}", s.contact_model),
        Err(e) => {
            assert_eq!(e.parameter(), Some(parameter), "{e}");
            assert!(e.to_string().contains(parameter), "{e}");
        }
    }
}

#[test]
fn each_law_rejects_its_own_bad_values() {
    let mut s = base(ModelKind::Luding);
    s.laws.luding.luding_loading_stiffness = Some(100.0);
    s.laws.luding.luding_max_unloading_stiffness = Some(50.0);
    names(&s, "luding_max_unloading_stiffness");
    s.laws.luding.luding_max_unloading_stiffness = Some(500.0);
    s.laws.luding.luding_plasticity_depth = 0.0;
    names(&s, "luding_plasticity_depth");

    let mut s = base(ModelKind::PashaSimplified);
    s.laws.pasha_simplified.pasha_pull_off_intercept = Some(1e-9);
    names(&s, "pasha_pull_off_intercept");

    let mut s = base(ModelKind::Pasha);
    s.laws.pasha.pasha_stiffness_law = PashaStiffnessLaw::LoadDependent;
    names(&s, "pasha_max_elastic_stiffness");
    s.laws.pasha.pasha_max_elastic_stiffness = Some(1.0);
    s.laws.stiffness.plastic_stiffness = Some(100.0);
    names(&s, "plastic_stiffness");

    let mut s = base(ModelKind::Tomas);
    s.laws.tomas.tomas_area_coefficient = 0.5;
    names(&s, "tomas_area_coefficient");
    s.laws.tomas.tomas_area_coefficient = 0.8;
    s.laws.tomas.tomas_repulsion_coefficient = 0.9;
    names(&s, "tomas_repulsion_coefficient");

    let mut s = base(ModelKind::WaltonBraun);
    s.laws.stiffness.elastic_stiffness = Some(100.0);
    s.laws.stiffness.plastic_stiffness = Some(200.0);
    names(&s, "plastic_stiffness");

    let mut s = base(ModelKind::ThorntonNing);
    s.particle_yield_pressure = None;
    names(&s, "particle_yield_pressure");

    let mut s = base(ModelKind::Nan);
    s.restitution_coefficient = 0.0;
    names(&s, "restitution_coefficient");
    let mut s = base(ModelKind::Nan);
    s.particle_radius = f64::NAN;
    names(&s, "particle_radius");
    let mut s = base(ModelKind::Nan);
    s.wall_youngs_modulus = Some(f64::INFINITY);
    names(&s, "wall_youngs_modulus");
    let mut s = base(ModelKind::Nan);
    s.laws.stiffness.unloading_stiffness_reference = Some(1000.0);
    names(&s, "unloading_stiffness_reference");
}

#[test]
fn a_surface_energy_that_makes_k_cl_negative_names_the_largest_allowed() {
    let mut s = base(ModelKind::Nan);
    s.surface_energy = 100.0;
    let Err(ParamError::OutOfRange { name, allowed, .. }) = AnyLaw::from_scene(&s) else { panic!("expected OutOfRange") };
    assert_eq!(name, "surface_energy");
    // The bound it names is right: just below it the law builds, just above it fails.
    let bound: f64 = allowed.trim_start_matches("[0, ").split(')').next().unwrap().parse().unwrap();
    s.surface_energy = bound * 0.999;
    assert!(AnyLaw::from_scene(&s).is_ok());
    s.surface_energy = bound * 1.001;
    assert!(AnyLaw::from_scene(&s).is_err());
}

#[test]
fn every_model_builds_from_the_defaults_of_a_plain_scene() {
    for m in ModelKind::ALL {
        AnyLaw::from_scene(&base(m)).unwrap_or_else(|e| panic!("{m:?}: {e}"));
    }
}

#[test]
fn a_measured_unloading_line_must_start_after_yield() {
    let mut s = base(ModelKind::Nan);
    s.laws.stiffness.unloading_stiffness_reference = Some(1274.0);
    s.laws.stiffness.unloading_overlap_reference = Some(1e-9); // below alpha_y of about 10 nm
    names(&s, "unloading_overlap_reference");
    s.laws.stiffness.unloading_overlap_reference = Some(210.5e-9);
    assert!(AnyLaw::from_scene(&s).is_ok());
}
