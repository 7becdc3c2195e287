//! `modelDescription.xml` in the FMI 3.0 schema, from the same variable table as the FMI 2.0 one
//! (`model_description`): the value references, names, units, starts and ranges are the same, so a host
//! can move between the two versions by name or by reference. What differs is the standard's own:
//! typed elements (Float64, Int32, Boolean, String with a `Start` child), `instantiationToken` in place of
//! `guid`, the Co-Simulation capabilities of FMI 3.0 (Event Mode, early return), and a `ModelStructure`
//! that names unknowns by value reference and lists the event indicators (FMI 3.0 Sec. 2.4.8).

use super::model_description::{escape, units_categories_experiment};
use super::variables::{format_real, Causality, Role, VarType, Variable};
use super::UnitInfo;
use std::fmt::Write;

/// The FMI 3.0 element name of a variable type.
pub fn element(t: VarType) -> &'static str {
    match t {
        VarType::Real => "Float64",
        VarType::Integer => "Int32",
        VarType::Boolean => "Boolean",
        VarType::String => "String",
    }
}

/// The whole FMI 3.0 `modelDescription.xml` of a unit, with the given instantiation token.
pub fn xml(unit: &UnitInfo, token: &str) -> String {
    let mut x = String::new();
    let id = unit.model_identifier;
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"{id}\" instantiationToken=\"{token}\" description=\"{}\" generationTool=\"powderfmu {}\" variableNamingConvention=\"flat\">",
        escape(unit.description),
        env!("CARGO_PKG_VERSION"),
    );
    if unit.model_exchange {
        let _ = writeln!(x, "  <ModelExchange modelIdentifier=\"{id}\" canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\" needsCompletedIntegratorStep=\"true\"/>");
    }
    // Early return and Event Mode where a step has events inside it: the sphere's contact (the other
    // units' contacts change only where the master changes their inputs, at communication points).
    // With intermediate updates at those events: the master reads the outputs there and may end the step.
    let events = if unit.returns_early {
        " mightReturnEarlyFromDoStep=\"true\" hasEventMode=\"true\" providesIntermediateUpdate=\"true\" canReturnEarlyAfterIntermediateUpdate=\"true\""
    } else {
        ""
    };
    let _ = writeln!(
        x,
        "  <CoSimulation modelIdentifier=\"{id}\" canHandleVariableCommunicationStepSize=\"true\" canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\"{events}/>"
    );
    x.push_str(&units_categories_experiment(unit, "fmi3"));
    x.push_str("  <ModelVariables>\n");
    for (vr, v) in unit.variables.iter().enumerate() {
        x.push_str(&variable_xml(unit, vr, v));
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let refs =
        |pred: &dyn Fn(&Variable) -> bool| -> Vec<usize> { unit.variables.iter().enumerate().filter(|(_, v)| pred(v)).map(|(i, _)| i).collect() };
    let outputs = refs(&|v| v.causality == Causality::Output);
    // In the order of the states (the derivative of state k is the k-th), as FMI 3.0 orders them.
    let mut derivatives = refs(&|v| matches!(v.role, Role::Derivative(_)));
    derivatives.sort_by_key(|&i| if let Role::Derivative(k) = unit.variables[i].role { k } else { usize::MAX });
    let mut initial = outputs.clone();
    initial.extend(refs(&|v| matches!(v.role, Role::State(_) | Role::Derivative(_)) && v.start.is_none()));
    initial.sort_unstable();
    initial.dedup();
    let mut indicators = refs(&|v| matches!(v.role, Role::Indicator(_)));
    indicators.sort_by_key(|&i| if let Role::Indicator(k) = unit.variables[i].role { k } else { usize::MAX });
    for (tag, list) in
        [("Output", &outputs), ("ContinuousStateDerivative", &derivatives), ("InitialUnknown", &initial), ("EventIndicator", &indicators)]
    {
        if tag == "EventIndicator" && !unit.model_exchange {
            continue;
        }
        for vr in list {
            let _ = writeln!(x, "    <{tag} valueReference=\"{vr}\"/>");
        }
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

fn variable_xml(unit: &UnitInfo, vr: usize, v: &Variable) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "    <{} name=\"{}\" valueReference=\"{vr}\" description=\"{}\" causality=\"{}\" variability=\"{}\"",
        element(v.var_type),
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
    if unit.returns_early && v.causality == Causality::Output {
        s.push_str(" intermediateUpdate=\"true\"");
    }
    if v.var_type == VarType::Real {
        if !v.unit.is_empty() {
            let _ = write!(s, " unit=\"{}\"", escape(v.unit));
        }
        if let Some(n) = v.nominal {
            let _ = write!(s, " nominal=\"{}\"", format_real(n));
        }
        if let Role::Derivative(k) = v.role {
            let state = unit.variables.iter().position(|w| w.role == Role::State(k)).expect("every derivative has its state");
            let _ = write!(s, " derivative=\"{state}\"");
        }
    }
    if let Some(m) = v.min {
        let _ = write!(s, " min=\"{}\"", format_real(m));
    }
    if let Some(m) = v.max {
        let _ = write!(s, " max=\"{}\"", format_real(m));
    }
    match (&v.start, v.var_type) {
        (Some(start), VarType::String) => {
            let _ = write!(s, ">\n      <Start value=\"{}\"/>\n    </String>\n", escape(&start.xml_text()));
        }
        (Some(start), _) => {
            let _ = writeln!(s, " start=\"{}\"/>", escape(&start.xml_text()));
        }
        (None, _) => s.push_str("/>\n"),
    }
    s
}
