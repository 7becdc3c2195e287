//! The one table of the normal contact laws (docs/architecture.md, "Contact law conventions"), the way LAMMPS registers a granular sub-model in
//! one line. Each line declares a law: its variant name, its module (whose name is its scene name,
//! `contact_model`), its type, and whether its branches are straight lines for a fixed history (what the
//! `exact` integrator needs). The first line is the default law.
//!
//! Everything that lists the laws is generated from this table: `ModelKind` with its names and choice
//! list (`scene/mod.rs`), `AnyLaw`, `AnyHistory` and `LawOptions` with their dispatch (`law/mod.rs`), and the bed's engines
//! compiled per law (`bed/any.rs`, `bed/interaction.rs`). What a law says about itself beyond the table
//! (its options and how a pair builds it, its tangential stiffness, its damping after yield) it says in
//! its own file, in its `LawInfo` impl.
//!
//! Adding a law: write its file (the law, `NormalLaw`, `LawInfo`), declare the module in `law/mod.rs`,
//! and add one line here (docs/models.md, "Adding a law").

/// Calls `$then! { $d; rows }` with the table's rows `Variant, module, Type, piecewise_linear;`. `$d` is
/// a `$` token handed through, so that a consumer can define a macro of its own from the rows.
#[macro_export]
macro_rules! law_table {
    ($then:ident; $d:tt) => {
        $then! { $d;
            Nan, nan, $crate::law::nan::Nan, true;
            Pasha, pasha, $crate::law::pasha::Pasha, true;
            PashaSimplified, pasha_simplified, $crate::law::pasha_simplified::PashaSimplified, true;
            Luding, luding, $crate::law::luding::Luding, true;
            ThorntonNing, thornton_ning, $crate::law::thornton_ning::ThorntonNing, false;
            Tomas, tomas, $crate::law::tomas::Tomas, false;
            Hertz, hertz, $crate::law::hertz::Hertz, false;
            Jkr, jkr, $crate::law::jkr::Jkr, false;
            JkrModified, jkr_modified, $crate::law::jkr_modified::JkrModified, false;
            Linear, linear, $crate::law::linear::Linear, true;
            WaltonBraun, walton_braun, $crate::law::walton_braun::WaltonBraun, true;
        }
    };
}

/// The names of the rows' modules, comma-separated, as one string literal.
#[macro_export]
macro_rules! join_names {
    ($first:ident $(, $rest:ident)*) => {
        concat!(stringify!($first) $(, ", ", stringify!($rest))*)
    };
}
