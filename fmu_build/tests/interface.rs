//! The checked-in interface files must be what the variable tables generate (docs/architecture.md, "One vocabulary"): a change of a
//! unit's variables shows up in review as a change of `modelDescription/<Unit>.xml` and its docs table.

use fmu_build::interface;
use powderfmu::units::{self, variables::Causality};

const FIX: &str = "run `cargo run -p fmu_build -- --update-interface` and commit the result";

#[test]
fn checked_in_model_descriptions_match_the_variable_tables() {
    for unit in units::all() {
        let path = interface::model_description_path(unit);
        let checked_in = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}; {FIX}", path.display()));
        assert!(checked_in == unit.model_description(), "{} differs from the variable table of {}; {FIX}", path.display(), unit.model_identifier);
    }
}

#[test]
fn checked_in_fmi3_model_descriptions_match_the_variable_tables() {
    for unit in units::all() {
        let path = interface::model_description_fmi3_path(unit);
        let checked_in = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}; {FIX}", path.display()));
        assert!(
            checked_in == unit.model_description_fmi3(),
            "{} differs from the variable table of {}; {FIX}",
            path.display(),
            unit.model_identifier
        );
    }
}

#[test]
fn docs_tables_match_the_variable_tables() {
    for unit in units::all() {
        let path = interface::docs_path(unit);
        let page = std::fs::read_to_string(&path).unwrap();
        assert!(interface::docs_with_table(&page, unit).unwrap() == page, "the variable table in {} is out of date; {FIX}", path.display());
    }
}

#[test]
fn every_scene_key_is_a_parameter_of_both_contact_units_and_names_are_unique() {
    for unit in units::all() {
        let mut names: Vec<&str> = unit.variables.iter().map(|v| v.name.as_str()).collect();
        names.sort_unstable();
        let n = names.len();
        names.dedup();
        assert_eq!(names.len(), n, "{}: duplicate variable names", unit.model_identifier);
        // The DEM units' contact laws are those of their bed files.
        if [units::ball_indentation::MODEL_IDENTIFIER, units::unconfined_compression::MODEL_IDENTIFIER].contains(&unit.model_identifier) {
            continue;
        }
        for key in powderfmu::scene::KEYS.iter() {
            let v = &unit.variables[unit.vr(key.name).expect("a variable of the unit")];
            assert_eq!(v.causality, Causality::Parameter, "{}", key.name);
        }
    }
}

#[test]
fn guids_differ_between_units_and_change_with_the_interface() {
    let all = units::all();
    assert_ne!(all[0].guid(), all[1].guid());
    let before = units::particle_wall_impact::info().guid();
    // A fresh description with one changed word (the GUID is cached per description).
    let mut changed = units::particle_wall_impact::info();
    changed.variables[0].description.push('!');
    assert_ne!(changed.guid(), before);
    // The FMI 3.0 token: its own hash, changed by the same edit, never the GUID.
    let token = units::particle_wall_impact::info().instantiation_token();
    assert_ne!(token, before);
    assert_ne!(changed.instantiation_token(), token);
}
