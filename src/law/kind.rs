//! `ModelKind`: the laws a scene can name, generated from the rows of `law_table!` (`table.rs`).

use crate::error::ParamError;
use crate::vocabulary::{choice_text, unknown_choice, Field, Key};
use serde_json::Value;

/// Defines `ModelKind` from the rows of `law_table!`.
macro_rules! define_model_kind {
    ($d:tt; $($variant:ident, $module:ident, $ty:ty, $pl:literal;)*) => {
        /// The normal contact laws a scene can name: the rows of `law_table!` (`src/law/table.rs`), in its
        /// order.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum ModelKind {
            $(
            /// One row of `law_table!`; its scene name is the row's module name (`ModelKind::name`).
            $variant,
            )*
        }

        impl ModelKind {
            /// Every law, in the table's order.
            pub const ALL: [ModelKind; [$(stringify!($module)),*].len()] = [$(ModelKind::$variant),*];

            /// The scene names, in the table's order.
            pub const NAMES: &'static [&'static str] = &[$(stringify!($module)),*];

            /// The scene name (`contact_model`).
            pub const fn name(self) -> &'static str {
                match self {
                    $(ModelKind::$variant => stringify!($module),)*
                }
            }

            /// Whether every branch is a straight line for a fixed history (the laws the `exact`
            /// integrator solves in closed form).
            pub fn is_piecewise_linear(self) -> bool {
                match self {
                    $(ModelKind::$variant => $pl,)*
                }
            }
        }
    };
}

crate::law_table!(define_model_kind; $);

impl ModelKind {
    /// The default law: the first line of the table.
    pub const DEFAULT: ModelKind = ModelKind::ALL[0];

    /// The scene names of the piecewise-linear laws, comma-separated.
    pub fn piecewise_linear_names() -> String {
        ModelKind::ALL.iter().filter(|m| m.is_piecewise_linear()).map(|m| m.name()).collect::<Vec<_>>().join(", ")
    }

    /// The law of a scene name (`contact_model`); an unknown name is an error that lists the names.
    pub fn parse(s: &str) -> Result<ModelKind, ParamError> {
        ModelKind::ALL.iter().copied().find(|m| m.name() == s).ok_or_else(|| unknown_choice("contact_model", s, ModelKind::NAMES))
    }
}

impl Field for ModelKind {
    fn parse(name: &'static str, value: &Value) -> Result<ModelKind, ParamError> {
        ModelKind::parse(choice_text(name, value)?)
    }
    fn check(&self, _key: &Key) -> Result<(), ParamError> {
        Ok(())
    }
}
