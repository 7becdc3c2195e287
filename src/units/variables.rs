//! The variable table of a unit (docs/architecture.md, "One vocabulary"): every FMU variable defined once, with its value reference,
//! causality, variability, unit, start, range and description. The `modelDescription.xml`, the value
//! reference dispatch of the C ABI and the docs tables are all generated from it.

/// The FMI 2.0 base type of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarType {
    /// A real number (FMI 3.0 Float64).
    Real,
    /// A 32-bit integer (FMI 3.0 Int32).
    Integer,
    /// A boolean.
    Boolean,
    /// A string.
    String,
}

impl VarType {
    /// The type's name in the FMI 2.0 model description ("Real", "Integer", "Boolean", "String").
    pub fn xml_name(self) -> &'static str {
        match self {
            VarType::Real => "Real",
            VarType::Integer => "Integer",
            VarType::Boolean => "Boolean",
            VarType::String => "String",
        }
    }
}

/// The FMI causality of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// A parameter: settable until the end of Initialization Mode, fixed after.
    Parameter,
    /// An input the host sets during the simulation.
    Input,
    /// An output the unit calculates.
    Output,
    /// A calculated local (continuous states, their derivatives, event indicators).
    Local,
    /// The independent variable, time.
    Independent,
}

impl Causality {
    /// The causality as the model description writes it.
    pub fn xml_name(self) -> &'static str {
        match self {
            Causality::Parameter => "parameter",
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Local => "local",
            Causality::Independent => "independent",
        }
    }
}

/// The FMI variability of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variability {
    /// Fixed after initialization (the parameters).
    Fixed,
    /// Changes only at events (the outputs that are not reals).
    Discrete,
    /// May change continuously in time (real inputs, outputs and locals).
    Continuous,
}

impl Variability {
    /// The variability as the model description writes it.
    pub fn xml_name(self) -> &'static str {
        match self {
            Variability::Fixed => "fixed",
            Variability::Discrete => "discrete",
            Variability::Continuous => "continuous",
        }
    }
}

/// A start value (also the value a fresh instance holds).
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A Real value.
    Real(f64),
    /// An Integer value.
    Integer(i32),
    /// A Boolean value.
    Boolean(bool),
    /// A String value.
    String(String),
}

impl Value {
    /// The type of the value.
    pub fn var_type(&self) -> VarType {
        match self {
            Value::Real(_) => VarType::Real,
            Value::Integer(_) => VarType::Integer,
            Value::Boolean(_) => VarType::Boolean,
            Value::String(_) => VarType::String,
        }
    }

    /// The value as the XML `start` attribute writes it (shortest text that reads back exactly).
    pub fn xml_text(&self) -> String {
        match self {
            Value::Real(x) => format_real(*x),
            Value::Integer(i) => i.to_string(),
            Value::Boolean(b) => b.to_string(),
            Value::String(s) => s.clone(),
        }
    }

    /// The text of a String value ("" for the other types).
    pub fn as_str(&self) -> &str {
        match self {
            Value::String(s) => s,
            _ => "",
        }
    }

    /// The value as a real: an Integer converted, a Boolean as 0 or 1, a String NaN.
    pub fn as_real(&self) -> f64 {
        match self {
            Value::Real(x) => *x,
            Value::Integer(i) => f64::from(*i),
            Value::Boolean(b) => f64::from(u8::from(*b)),
            Value::String(_) => f64::NAN,
        }
    }
}

/// Shortest round-trip text of a real, with an exponent for very small and large magnitudes.
pub fn format_real(x: f64) -> String {
    if x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e6) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// How a state variable and its derivative are tied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// An ordinary variable.
    Plain,
    /// The i-th continuous state (0-based, ME).
    State(usize),
    /// The derivative of the i-th continuous state.
    Derivative(usize),
    /// The i-th event indicator (0-based, ME): a variable so that FMI 3.0's ModelStructure can name it.
    Indicator(usize),
    /// The independent variable, time.
    Time,
}

/// One FMU variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// The variable's name.
    pub name: String,
    /// Its causality.
    pub causality: Causality,
    /// Its variability.
    pub variability: Variability,
    /// Start value for parameters, inputs and exact states; `None` means initial="calculated".
    pub start: Option<Value>,
    /// Its type.
    pub var_type: VarType,
    /// Unit name (defined in `UNITS`), or "" for a dimensionless value.
    pub unit: &'static str,
    /// The smallest value a set may give, in the variable's unit (the XML `min`); None: no bound.
    pub min: Option<f64>,
    /// The largest value a set may give, in the variable's unit (the XML `max`); None: no bound.
    pub max: Option<f64>,
    /// The nominal value, in the variable's unit (the XML `nominal`); None: none given.
    pub nominal: Option<f64>,
    /// The description the model description and the docs give.
    pub description: String,
    /// Whether it is a plain variable, a continuous state, a derivative, an event indicator or time.
    pub role: Role,
}

impl Variable {
    #[allow(clippy::too_many_arguments)] // every column of a variable table row; called by the named constructors below
    fn new(
        name: &str,
        causality: Causality,
        variability: Variability,
        var_type: VarType,
        start: Option<Value>,
        unit: &'static str,
        description: &str,
        role: Role,
    ) -> Variable {
        Variable {
            name: name.into(),
            causality,
            variability,
            var_type,
            start,
            unit,
            min: None,
            max: None,
            nominal: None,
            description: description.into(),
            role,
        }
    }

    /// A parameter with a start value (causality parameter, variability fixed, initial exact).
    pub fn parameter(name: &str, start: Value, unit: &'static str, description: &str) -> Variable {
        Variable::new(name, Causality::Parameter, Variability::Fixed, start.var_type(), Some(start), unit, description, Role::Plain)
    }

    /// A continuous real input, start 0.
    pub fn input(name: &str, unit: &'static str, description: &str) -> Variable {
        Variable::new(name, Causality::Input, Variability::Continuous, VarType::Real, Some(Value::Real(0.0)), unit, description, Role::Plain)
    }

    /// A calculated output.
    pub fn output(name: &str, var_type: VarType, unit: &'static str, description: &str) -> Variable {
        let variability = if var_type == VarType::Real { Variability::Continuous } else { Variability::Discrete };
        Variable::new(name, Causality::Output, variability, var_type, None, unit, description, Role::Plain)
    }

    /// The independent variable `time` (FMI 3.0 needs exactly one; the value is the instance's time).
    pub fn time() -> Variable {
        Variable::new("time", Causality::Independent, Variability::Continuous, VarType::Real, None, "s", "simulation time", Role::Time)
    }

    /// The event indicators of the contact units (`Contact::indicators`), dimensionless, as locals.
    pub fn contact_indicators() -> Vec<Variable> {
        [
            ("event_indicator_lower", "event indicator: distance above the lower bound of the accepted branch, in nominal overlaps (or the overlap rate at a bound it leaves), positive while the branch holds"),
            ("event_indicator_upper", "event indicator: distance below the upper bound of the accepted branch, in nominal overlaps (or minus the overlap rate at the largest overlap), positive while the branch holds"),
            ("event_indicator_rate", "event indicator: the overlap rate in nominal rates (a turning point at the largest overlap), or below the largest overlap its distance from it"),
        ]
        .iter()
        .enumerate()
        .map(|(i, (name, doc))| Variable::local(name, "", doc, Role::Indicator(i)))
        .collect()
    }

    /// A calculated local continuous real (states and derivatives).
    pub fn local(name: &str, unit: &'static str, description: &str, role: Role) -> Variable {
        Variable::new(name, Causality::Local, Variability::Continuous, VarType::Real, None, unit, description, role)
    }

    /// The same variable with `min` and `max` (None: no bound).
    pub fn with_range(mut self, min: Option<f64>, max: Option<f64>) -> Variable {
        self.min = min;
        self.max = max;
        self
    }

    /// The same variable with a nominal value.
    pub fn with_nominal(mut self, nominal: f64) -> Variable {
        self.nominal = Some(nominal);
        self
    }

    /// The same variable with another role.
    pub fn with_role(mut self, role: Role) -> Variable {
        self.role = role;
        self
    }

    /// The value a fresh instance holds: the start value, or zero of the type for calculated ones.
    pub fn initial_value(&self) -> Value {
        match (&self.start, self.var_type) {
            (Some(v), _) => v.clone(),
            (None, VarType::Real) => Value::Real(0.0),
            (None, VarType::Integer) => Value::Integer(0),
            (None, VarType::Boolean) => Value::Boolean(false),
            (None, VarType::String) => Value::String(String::new()),
        }
    }

    /// The FMI `initial` attribute.
    pub fn initial(&self) -> Option<&'static str> {
        match self.causality {
            Causality::Independent => None,
            Causality::Parameter | Causality::Input => Some("exact"),
            _ => Some(if self.start.is_some() { "exact" } else { "calculated" }),
        }
    }
}

/// A unit of `UnitDefinitions`: name and SI base-unit exponents (kg, m, s, rad).
pub struct UnitDef {
    /// The unit's name, as variables give it ("m/s").
    pub name: &'static str,
    /// Exponent of kg.
    pub kg: i32,
    /// Exponent of m.
    pub m: i32,
    /// Exponent of s.
    pub s: i32,
    /// Exponent of rad (angles and spins).
    pub rad: i32,
}

/// Every unit a variable may use.
pub const UNITS: &[UnitDef] = &[
    UnitDef { name: "s", kg: 0, m: 0, s: 1, rad: 0 },
    UnitDef { name: "m", kg: 0, m: 1, s: 0, rad: 0 },
    UnitDef { name: "m2", kg: 0, m: 2, s: 0, rad: 0 },
    UnitDef { name: "m/s", kg: 0, m: 1, s: -1, rad: 0 },
    UnitDef { name: "m/s2", kg: 0, m: 1, s: -2, rad: 0 },
    UnitDef { name: "1/s", kg: 0, m: 0, s: -1, rad: 0 },
    UnitDef { name: "1/m", kg: 0, m: -1, s: 0, rad: 0 },
    UnitDef { name: "kg/m3", kg: 1, m: -3, s: 0, rad: 0 },
    UnitDef { name: "Pa", kg: 1, m: -1, s: -2, rad: 0 },
    UnitDef { name: "N", kg: 1, m: 1, s: -2, rad: 0 },
    UnitDef { name: "N/m", kg: 1, m: 0, s: -2, rad: 0 },
    UnitDef { name: "J", kg: 1, m: 2, s: -2, rad: 0 },
    UnitDef { name: "W", kg: 1, m: 2, s: -3, rad: 0 },
    UnitDef { name: "J/m2", kg: 1, m: 0, s: -2, rad: 0 },
    UnitDef { name: "rad", kg: 0, m: 0, s: 0, rad: 1 },
    UnitDef { name: "rad/s", kg: 0, m: 0, s: -1, rad: 1 },
    UnitDef { name: "rad/s2", kg: 0, m: 0, s: -2, rad: 1 },
    UnitDef { name: "N/s", kg: 1, m: 1, s: -3, rad: 0 },
];

/// The FMI unit name of a scene key's unit text ("-" is dimensionless).
pub fn fmi_unit(scene_unit: &str) -> &'static str {
    match scene_unit {
        "m" => "m",
        "kg/m^3" => "kg/m3",
        "Pa" => "Pa",
        "1/s" => "1/s",
        "1/m" => "1/m",
        "J/m^2" => "J/m2",
        "N/m" => "N/m",
        "N" => "N",
        "m/s" => "m/s",
        "m/s^2" => "m/s2",
        "J" => "J",
        _ => "",
    }
}

/// Declares a unit's own variables, in value-reference order, each with the name the model uses for it:
/// `field: Variable::...,`. Generates `own_variables()` (the table) and `REFS`, a `Refs` struct whose
/// fields are the value references, the positions in that same table, fixed at compile time.
macro_rules! variable_table {
    ($($field:ident: $variable:expr,)*) => {
        /// Value references of the unit's own variables (their positions in `own_variables()`).
        #[derive(Debug, Clone, Copy)]
        struct Refs {
            $($field: usize,)*
        }

        const REFS: Refs = {
            let mut next = 0usize;
            let refs = Refs {
                $($field: {
                    let vr = next;
                    next += 1;
                    vr
                },)*
            };
            let _ = next;
            refs
        };

        /// The unit's own variables (the scene keys follow them).
        fn own_variables() -> Vec<Variable> {
            vec![$($variable,)*]
        }
    };
}
