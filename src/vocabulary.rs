//! The parameter vocabulary (docs/architecture.md, "One vocabulary"; layer 0): one key defined once, with
//! its name, unit, typed default, allowed range and meaning. A group of keys is a typed struct declared
//! with `scene_options!`; the struct, its defaults, its part of the key table, its reading from JSON and
//! its range checks are all generated from that one declaration. The laws declare their options with it,
//! `scene::Scene` composes them, and `bed::scene` reads the bed's keys with its helpers.

use crate::error::{check_closed_low, check_open, check_open_closed, open_closed_text, range_text, ParamError};
use serde_json::{Map, Value};

/// What kind of value a key takes, and so how it reaches an FMU (`units::scene_params`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyKind {
    /// One of a set of names (a String parameter).
    Choice,
    /// A number every scene must give.
    Required,
    /// A number with a fixed default.
    Number,
    /// A number whose default is derived from other keys (an FMU's Real parameter uses 0 for "derive").
    Derived,
}

/// A key's default, typed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KeyDefault {
    /// No default: every scene gives it.
    Required,
    /// This number.
    Number(f64),
    /// Derived from other keys, as the text says ("pi R* p_y", "rigid", "none").
    Derived(&'static str),
    /// This name, one of `allowed`.
    Choice {
        /// The default name.
        default: &'static str,
        /// Every name the key accepts.
        allowed: &'static [&'static str],
    },
}

/// The values a number may take (finite always).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Range {
    /// lo < x < hi.
    Open(f64, f64),
    /// lo <= x < hi.
    ClosedLow(f64, f64),
    /// lo < x <= hi.
    OpenClosed(f64, f64),
    /// A choice: its names are its range.
    Names,
}

/// One scene key.
#[derive(Debug, Clone, Copy)]
pub struct Key {
    /// The key's name in a scene.
    pub name: &'static str,
    /// The unit of its value ("-" for none).
    pub unit: &'static str,
    /// Its default.
    pub default: KeyDefault,
    /// The values it accepts.
    pub range: Range,
    /// Its meaning, as the help and the FMU's description print it.
    pub doc: &'static str,
}

impl Key {
    /// The kind of value the key takes, from its default.
    pub fn kind(&self) -> KeyKind {
        match self.default {
            KeyDefault::Required => KeyKind::Required,
            KeyDefault::Number(_) => KeyKind::Number,
            KeyDefault::Derived(_) => KeyKind::Derived,
            KeyDefault::Choice { .. } => KeyKind::Choice,
        }
    }

    /// The default as the help prints it: a number, a name, or how it is derived.
    pub fn default_text(&self) -> String {
        match self.default {
            KeyDefault::Required => "required".into(),
            KeyDefault::Number(x) => {
                let plain = format!("{x}");
                if plain.len() > 8 {
                    format!("{x:e}")
                } else {
                    plain
                }
            }
            KeyDefault::Derived(text) => text.into(),
            KeyDefault::Choice { default, .. } => default.into(),
        }
    }

    /// What the key accepts: a range with its unit, or the names of a choice.
    pub fn allowed_text(&self) -> String {
        let unit = if self.unit == "-" { "" } else { self.unit };
        match (self.range, self.default) {
            (Range::Open(lo, hi), _) => range_text(lo, hi, false, unit),
            (Range::ClosedLow(lo, hi), _) => range_text(lo, hi, true, unit),
            (Range::OpenClosed(lo, hi), _) => open_closed_text(lo, hi, unit),
            (Range::Names, KeyDefault::Choice { allowed, .. }) => allowed.join(", "),
            (Range::Names, _) => "any".into(),
        }
    }

    /// Checks a number against the key's range; the error names the key and its range with the unit.
    pub fn check(&self, value: f64) -> Result<f64, ParamError> {
        let unit = if self.unit == "-" { "" } else { self.unit };
        match self.range {
            Range::Open(lo, hi) => check_open(self.name, value, lo, hi, unit),
            Range::ClosedLow(lo, hi) => check_closed_low(self.name, value, lo, hi, unit),
            Range::OpenClosed(lo, hi) => check_open_closed(self.name, value, lo, hi, unit),
            Range::Names => Ok(value),
        }
    }
}

/// The type of one key's value: a number, an optional (derived) number, or a choice.
pub trait Field: Sized {
    /// Reads a value given in JSON (not null).
    fn parse(name: &'static str, value: &Value) -> Result<Self, ParamError>;
    /// Checks the value against its key's range.
    fn check(&self, key: &Key) -> Result<(), ParamError>;
}

impl Field for f64 {
    fn parse(name: &'static str, value: &Value) -> Result<f64, ParamError> {
        value.as_f64().ok_or_else(|| ParamError::Malformed { what: format!("`{name}` must be a number, got {value}") })
    }
    fn check(&self, key: &Key) -> Result<(), ParamError> {
        key.check(*self).map(|_| ())
    }
}

impl Field for Option<f64> {
    fn parse(name: &'static str, value: &Value) -> Result<Option<f64>, ParamError> {
        f64::parse(name, value).map(Some)
    }
    fn check(&self, key: &Key) -> Result<(), ParamError> {
        match self {
            Some(x) => key.check(*x).map(|_| ()),
            None => Ok(()),
        }
    }
}

/// The text of a choice given in JSON.
pub fn choice_text<'v>(name: &'static str, value: &'v Value) -> Result<&'v str, ParamError> {
    value.as_str().ok_or_else(|| ParamError::Malformed { what: format!("`{name}` must be a string, got {value}") })
}

/// The error for a name that is not one of a choice's.
pub fn unknown_choice(name: &'static str, value: &str, allowed: &[&str]) -> ParamError {
    ParamError::UnknownChoice { name: name.into(), value: value.into(), allowed: allowed.join(", ") }
}

/// The value of `name` in `map`, unless absent or null (null means "the default").
pub fn given<'m>(map: &'m Map<String, Value>, name: &str) -> Option<&'m Value> {
    map.get(name).filter(|v| !v.is_null())
}

/// The known name closest to `unknown` by edit distance, if it is close enough to be a typo.
pub fn nearest_name<'a>(unknown: &str, known: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let best = known.map(|name| (edit_distance(unknown, name), name)).min();
    match best {
        Some((d, name)) if d <= 3.max(unknown.len() / 4) => Some(name),
        _ => None,
    }
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != *cb)).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// A typed group of scene keys (generated by `scene_options!`).
pub trait Options: Sized {
    /// The group's own keys, in the order of its fields.
    const OWN_KEYS: &'static [Key];
    /// Appends every key of the group to `out`: its own, then those of the groups it nests.
    fn keys(out: &mut Vec<Key>) {
        out.extend_from_slice(Self::OWN_KEYS);
    }
    /// Every key at its default (a required key at NaN, which no range accepts).
    fn defaults() -> Self;
    /// Sets the keys `map` gives.
    fn read(&mut self, map: &Map<String, Value>) -> Result<(), ParamError>;
    /// Checks every value against its key's range.
    fn check(&self) -> Result<(), ParamError>;
}

/// The options of a law that has none of its own.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NoOptions;

impl Options for NoOptions {
    const OWN_KEYS: &'static [Key] = &[];
    fn defaults() -> NoOptions {
        NoOptions
    }
    fn read(&mut self, _map: &Map<String, Value>) -> Result<(), ParamError> {
        Ok(())
    }
    fn check(&self) -> Result<(), ParamError> {
        Ok(())
    }
}

/// Declares a choice: an enum whose variants have scene names, with `NAMES`, `name()` and `Field`.
#[macro_export]
macro_rules! choice_enum {
    ($(#[$meta:meta])* pub enum $ty:ident { $($(#[$vmeta:meta])* $variant:ident = $name:literal,)* }) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum $ty {
            $($(#[$vmeta])* $variant,)*
        }

        impl $ty {
            /// The scene names, in declaration order.
            pub const NAMES: &'static [&'static str] = &[$($name),*];

            /// The scene name.
            pub const fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name,)*
                }
            }
        }

        impl $crate::vocabulary::Field for $ty {
            fn parse(name: &'static str, value: &serde_json::Value) -> Result<$ty, $crate::ParamError> {
                let text = value.as_str().ok_or_else(|| $crate::ParamError::Malformed {
                    what: format!("`{name}` must be one of {}, got {value}", $ty::NAMES.join(", ")),
                })?;
                match text {
                    $($name => Ok($ty::$variant),)*
                    other => Err($crate::vocabulary::unknown_choice(name, other, $ty::NAMES)),
                }
            }
            fn check(&self, _key: &$crate::vocabulary::Key) -> Result<(), $crate::ParamError> {
                Ok(())
            }
        }
    };
}

/// Declares a typed group of scene keys, each once:
///
/// `name: kind(default), "unit", range, "meaning";` where kind is `required()` (an `f64` with no
/// default), `number(x)` (an `f64`), `derived("how")` (an `Option<f64>`, `None` until given) or
/// `choice(Type::Variant)` (a `choice_enum!`). The field's name is the key's name. Generates the struct,
/// its `Options` impl (key table, defaults, reading, range checks). A trailing `nests { field: Type, }`
/// nests other groups: read, checked and listed (`keys`) after this one's own keys.
#[macro_export]
macro_rules! scene_options {
    ($(#[$meta:meta])* pub struct $group:ident {
        $($field:ident: $kind:ident($($arg:tt)*), $unit:literal, $range:expr, $doc:expr;)*
    } $(nests { $($(#[$gmeta:meta])* $gfield:ident: $gty:ty,)* })?) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq)]
        pub struct $group {
            $(#[doc = $doc] pub $field: $crate::scene_options!(@type $kind($($arg)*)),)*
            $($($(#[$gmeta])* pub $gfield: $gty,)*)?
        }

        impl $crate::vocabulary::Options for $group {
            const OWN_KEYS: &'static [$crate::vocabulary::Key] = &[$($crate::vocabulary::Key {
                name: stringify!($field),
                unit: $unit,
                default: $crate::scene_options!(@default $kind($($arg)*)),
                range: $range,
                doc: $doc,
            },)*];

            fn keys(out: &mut Vec<$crate::vocabulary::Key>) {
                out.extend_from_slice(<$group as $crate::vocabulary::Options>::OWN_KEYS);
                $($(<$gty as $crate::vocabulary::Options>::keys(out);)*)?
            }

            fn defaults() -> $group {
                $group {
                    $($field: $crate::scene_options!(@value $kind($($arg)*)),)*
                    $($($gfield: <$gty as $crate::vocabulary::Options>::defaults(),)*)?
                }
            }

            fn read(&mut self, map: &serde_json::Map<String, serde_json::Value>) -> Result<(), $crate::ParamError> {
                $(if let Some(v) = $crate::vocabulary::given(map, stringify!($field)) {
                    self.$field = $crate::vocabulary::Field::parse(stringify!($field), v)?;
                })*
                $($($crate::vocabulary::Options::read(&mut self.$gfield, map)?;)*)?
                Ok(())
            }

            fn check(&self) -> Result<(), $crate::ParamError> {
                let mut keys = <$group as $crate::vocabulary::Options>::OWN_KEYS.iter();
                $($crate::vocabulary::Field::check(&self.$field, keys.next().expect("one key per field"))?;)*
                $($($crate::vocabulary::Options::check(&self.$gfield)?;)*)?
                Ok(())
            }
        }
    };
    (@type required()) => { f64 };
    (@type number($x:expr)) => { f64 };
    (@type derived($text:literal)) => { Option<f64> };
    (@type choice($ty:ident :: $variant:ident)) => { $ty };
    (@default required()) => { $crate::vocabulary::KeyDefault::Required };
    (@default number($x:expr)) => { $crate::vocabulary::KeyDefault::Number($x) };
    (@default derived($text:literal)) => { $crate::vocabulary::KeyDefault::Derived($text) };
    (@default choice($ty:ident :: $variant:ident)) => {
        $crate::vocabulary::KeyDefault::Choice { default: $ty::$variant.name(), allowed: $ty::NAMES }
    };
    (@value required()) => { f64::NAN };
    (@value number($x:expr)) => { $x };
    (@value derived($text:literal)) => { None };
    (@value choice($ty:ident :: $variant:ident)) => { $ty::$variant };
}
