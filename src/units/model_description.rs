//! `modelDescription.xml` (FMI 2.0) generated from a unit's variable table, and the Markdown table of
//! its variables for the docs. Both are pure functions of `UnitInfo`, so a test can compare them with
//! the checked-in copies under `modelDescription/` and `docs/`.

use super::variables::{Causality, Role, VarType, Variable, UNITS};
use super::UnitInfo;
use std::fmt::Write;

/// XML text with the five predefined entities escaped.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(c),
        }
    }
    out
}

/// The whole `modelDescription.xml` of a unit, with the given GUID.
pub fn xml(unit: &UnitInfo, guid: &str) -> String {
    let mut x = String::new();
    let id = unit.model_identifier;
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{id}\" guid=\"{guid}\" description=\"{}\" generationTool=\"powderfmu {}\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"{}\">",
        escape(unit.description),
        env!("CARGO_PKG_VERSION"),
        unit.n_event_indicators
    );
    if unit.model_exchange {
        let _ = writeln!(x, "  <ModelExchange modelIdentifier=\"{id}\" canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\" completedIntegratorStepNotNeeded=\"false\"/>");
    }
    let interpolate = if unit.can_interpolate_inputs { " canInterpolateInputs=\"true\"" } else { "" };
    let _ = writeln!(
        x,
        "  <CoSimulation modelIdentifier=\"{id}\" canHandleVariableCommunicationStepSize=\"true\"{interpolate} canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\"/>"
    );
    x.push_str(&units_categories_experiment(unit, "fmi2"));
    x.push_str("  <ModelVariables>\n");
    for (i, v) in unit.variables.iter().enumerate() {
        let _ = writeln!(x, "    <!-- index {} -->", i + 1);
        x.push_str(&variable_xml(unit, i, v));
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let index =
        |pred: &dyn Fn(&Variable) -> bool| -> Vec<usize> { unit.variables.iter().enumerate().filter(|(_, v)| pred(v)).map(|(i, _)| i + 1).collect() };
    let outputs = index(&|v| v.causality == Causality::Output);
    let derivatives = index(&|v| matches!(v.role, Role::Derivative(_)));
    let mut initial: Vec<usize> = outputs.clone();
    initial.extend(index(&|v| matches!(v.role, Role::State(_) | Role::Derivative(_)) && v.start.is_none()));
    initial.sort_unstable();
    initial.dedup();
    for (tag, list) in [("Outputs", &outputs), ("Derivatives", &derivatives), ("InitialUnknowns", &initial)] {
        if list.is_empty() {
            continue;
        }
        let _ = writeln!(x, "    <{tag}>");
        for i in list {
            let _ = writeln!(x, "      <Unknown index=\"{i}\"/>");
        }
        let _ = writeln!(x, "    </{tag}>");
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// `UnitDefinitions`, `LogCategories` and `DefaultExperiment`: the same text in FMI 2.0 and 3.0.
/// The unit definitions, the log categories (their statuses named with `status_prefix`, "fmi2" or
/// "fmi3") and the default experiment.
pub fn units_categories_experiment(unit: &UnitInfo, status_prefix: &str) -> String {
    let mut x = String::from("  <UnitDefinitions>\n");
    for u in UNITS.iter().filter(|u| unit.variables.iter().any(|v| v.unit == u.name)) {
        let mut attrs = String::new();
        for (name, e) in [("kg", u.kg), ("m", u.m), ("s", u.s), ("rad", u.rad)] {
            if e != 0 {
                let _ = write!(attrs, " {name}=\"{e}\"");
            }
        }
        let _ = writeln!(x, "    <Unit name=\"{}\">\n      <BaseUnit{attrs}/>\n    </Unit>", escape(u.name));
    }
    x.push_str("  </UnitDefinitions>\n  <LogCategories>\n");
    for (name, doc) in super::LOG_CATEGORIES {
        let _ = writeln!(x, "    <Category name=\"{name}\" description=\"{}\"/>", escape(&doc.replace("fmi2", status_prefix)));
    }
    x.push_str("  </LogCategories>\n");
    let _ = writeln!(
        x,
        "  <DefaultExperiment startTime=\"0\" stopTime=\"{}\" tolerance=\"1e-06\" stepSize=\"{}\"/>",
        super::variables::format_real(unit.stop_time),
        super::variables::format_real(unit.step_size)
    );
    x
}

fn variable_xml(unit: &UnitInfo, vr: usize, v: &Variable) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" description=\"{}\" causality=\"{}\" variability=\"{}\"",
        escape(&v.name),
        escape(&v.description),
        v.causality.xml_name(),
        v.variability.xml_name()
    );
    if let Some(init) = v.initial() {
        if !(v.causality == Causality::Parameter || v.causality == Causality::Input) {
            let _ = write!(s, " initial=\"{init}\"");
        }
    }
    s.push_str(">\n      <");
    s.push_str(v.var_type.xml_name());
    if v.var_type == VarType::Real {
        if !v.unit.is_empty() {
            let _ = write!(s, " unit=\"{}\"", escape(v.unit));
        }
        if let Role::Derivative(k) = v.role {
            let state = unit.variables.iter().position(|w| w.role == Role::State(k)).expect("every derivative has its state");
            let _ = write!(s, " derivative=\"{}\"", state + 1);
        }
        if let Some(n) = v.nominal {
            let _ = write!(s, " nominal=\"{}\"", super::variables::format_real(n));
        }
    }
    if let Some(m) = v.min {
        let _ = write!(s, " min=\"{}\"", super::variables::format_real(m));
    }
    if let Some(m) = v.max {
        let _ = write!(s, " max=\"{}\"", super::variables::format_real(m));
    }
    if let Some(start) = &v.start {
        let _ = write!(s, " start=\"{}\"", escape(&start.xml_text()));
    }
    s.push_str("/>\n    </ScalarVariable>\n");
    s
}

/// A Markdown table of the unit's variables, for its docs page.
pub fn markdown_table(unit: &UnitInfo) -> String {
    let mut s = String::from("| name | causality | type | unit | start | description |\n|---|---|---|---|---|---|\n");
    for v in &unit.variables {
        let start = v.start.as_ref().map(|x| x.xml_text()).unwrap_or_else(|| "calculated".into());
        let unit_text = if v.unit.is_empty() { "-" } else { v.unit };
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | {} |",
            v.name,
            v.causality.xml_name(),
            v.var_type.xml_name(),
            unit_text,
            start,
            v.description.replace('|', "\\|")
        );
    }
    s
}
