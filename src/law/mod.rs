//! Normal contact laws. Conventions (docs/architecture.md, "Contact law conventions"): overlap `alpha > 0` is compression, force `f > 0` is
//! repulsion. Every law answers one question through `NormalLaw::evaluate`: at this overlap, with this
//! history, what is the force, which branch is it on, how stiff is that branch, over which overlaps does
//! the branch hold, and what would the history be if this state were accepted. Laws never integrate in
//! time, never allocate and never panic.

pub mod damping;
pub mod hertz;
pub mod jkr;
pub mod jkr_modified;
mod kind;
pub mod linear;
pub mod luding;
pub mod nan;
pub mod nan_params;
pub mod params;
pub mod pasha;
pub mod pasha_simplified;
mod table;
pub(crate) mod tangential;
pub mod thornton_ning;
pub mod tomas;
pub mod walton_braun;

use crate::error::ParamError;
use crate::vocabulary::{Key, Options};
pub use kind::ModelKind;
use params::Effective;
use serde_json::{Map, Value};
use tangential::TangentialModel;

/// The branch of a force-overlap diagram the contact is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Branch {
    /// Not in contact, no force.
    Separated,
    /// Not in contact, but attracted (the van der Waals tail of the Tomas law).
    Attraction,
    /// Reversible elastic branch (also its tensile part down to the pull-off point).
    Elastic,
    /// Plastic loading: the history grows with the overlap.
    Plastic,
    /// Beyond the pull-off point (lines AB and EF of 000 Fig. 1; Luding's adhesion limit).
    Adhesive,
    /// The Tomas reloading curve (003 Table 1).
    Reloading,
}

impl Branch {
    /// The integer contact state of the FMUs: 0 separated, 1 elastic, 2 plastic, 3 adhesive,
    /// 4 reloading, 5 attracted without contact.
    pub fn contact_state(self) -> i32 {
        match self {
            Branch::Separated => 0,
            Branch::Elastic => 1,
            Branch::Plastic => 2,
            Branch::Adhesive => 3,
            Branch::Reloading => 4,
            Branch::Attraction => 5,
        }
    }

    /// Whether the surfaces touch: false for `Separated` and `Attraction`, true on every other branch.
    pub fn in_contact(self) -> bool {
        !matches!(self, Branch::Separated | Branch::Attraction)
    }
}

/// The answer of a law at one overlap.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Evaluation<H> {
    /// Normal force f [N], positive repulsive.
    pub force: f64,
    /// df/dalpha on this branch [N/m] (for damping, time steps and Jacobians).
    pub stiffness: f64,
    /// The branch the contact is on at this overlap.
    pub branch: Branch,
    /// The branch holds for `lower <= alpha <= upper` with the history passed in; outside it another
    /// branch (or a history update) applies. Integrators land on these to switch exactly.
    pub lower: f64,
    /// Upper end of the overlap interval on which this branch holds [m] (see `lower`).
    pub upper: f64,
    /// The history to keep if this state is accepted (never stored by the law itself).
    pub history: H,
}

impl<H> Evaluation<H> {
    /// Not in contact: no force, no stiffness; contact can form again at `upper`.
    #[inline]
    pub fn separated(upper: f64, history: H) -> Evaluation<H> {
        Evaluation { force: 0.0, stiffness: 0.0, branch: Branch::Separated, lower: f64::NEG_INFINITY, upper, history }
    }
}

/// The interface every normal law offers.
pub trait NormalLaw {
    /// What the contact remembers: a small `Copy` value.
    type History: Copy + std::fmt::Debug + PartialEq;

    /// The history of a contact that has never touched.
    fn initial_history(&self) -> Self::History;

    /// Force, branch, stiffness, branch interval and updated history at overlap `alpha`.
    fn evaluate(&self, alpha: f64, history: &Self::History) -> Evaluation<Self::History>;

    /// Whether the contact has yielded (selects the damping factor beta, 000 Sec. 2.3).
    fn has_yielded(&self, history: &Self::History) -> bool;

    /// The normal load of the Coulomb limit, shifted by the law's adhesion (000 Eq. 23, 004 Eqs. 4.27-4.28,
    /// 3.49, 3.75, 003 Eq. 10). The sliding limit is `mu * max(this, 0)`.
    fn sliding_normal_force(&self, force: f64, alpha: f64, history: &Self::History) -> f64;

    /// The maximum tensile force the contact can take with this history (pull-off force, positive) [N].
    fn pull_off_force(&self, history: &Self::History) -> f64;

    /// The permanent (plastic) overlap of this history [m]: where the unloading branch meets zero force.
    fn plastic_overlap(&self, history: &Self::History) -> f64;

    /// The contact radius at this overlap, for the laws that define one (Hertz and the JKR curves) [m].
    /// Mindlin's tangential stiffness 8 G* a uses it.
    fn contact_radius(&self, _alpha: f64, _history: &Self::History) -> Option<f64> {
        None
    }

    /// The DEM force loop's one call per contact and step: the evaluation, the damping stiffness and the
    /// contact radius together. The JKR laws override it so that their contact radius (a Newton solve)
    /// is found once instead of three times.
    #[inline(always)]
    fn evaluate_with_radius(&self, alpha: f64, history: &Self::History) -> (Evaluation<Self::History>, f64, Option<f64>) {
        let ev = self.evaluate(alpha, history);
        let k_damp = self.damping_stiffness(alpha, &ev.history, ev.stiffness);
        let a = self.contact_radius(alpha, &ev.history);
        (ev, k_damp, a)
    }

    /// `evaluate_with_radius` with the contact radius of the same contact one step earlier as a starting
    /// guess (0 if none): the JKR laws then polish it with two or three Newton steps instead of solving
    /// their quartic from scratch. Other laws ignore the guess.
    #[inline(always)]
    fn evaluate_near(&self, alpha: f64, history: &Self::History, _radius_guess: f64) -> (Evaluation<Self::History>, f64, Option<f64>) {
        self.evaluate_with_radius(alpha, history)
    }

    /// The radius Mindlin's tangential stiffness 8 G* r is taken at, given the contact radius the law
    /// returned with its evaluation (`evaluate_near`): by default that radius. The modified JKR law with
    /// `jkr_stiffness_radius = hertz` takes Hertz's sqrt(R* alpha) instead (EDEM's JKR cohesion).
    #[inline(always)]
    fn mindlin_radius(&self, _alpha: f64, _history: &Self::History, contact_radius: Option<f64>) -> Option<f64> {
        contact_radius
    }

    /// The stiffness k_n of the viscous damping 2 gamma sqrt(m* k_n) (000 Eqs. 24-25) [N/m]: by default the
    /// magnitude of the branch stiffness. The JKR curves use 2 E* a, because their branch stiffness is
    /// infinite at detachment.
    fn damping_stiffness(&self, _alpha: f64, _history: &Self::History, branch_stiffness: f64) -> f64 {
        branch_stiffness.abs()
    }

    /// Where a branch ends in a vertical tangent at its lower bound (the JKR curves under displacement
    /// control, where d alpha / d a = 0 and f - f_d grows as sqrt(alpha - alpha_d), 000 App. B): the
    /// width [m] of the zone above that bound over which the curve bends to vertical (from the pull-off
    /// overlap down to detachment). None where the lower end is smooth. Model Exchange crosses the last
    /// part of that zone in Event Mode (`impact::Sphere::accept_crossing`), since the solution's higher
    /// derivatives are unbounded there.
    fn vertical_end(&self, _branch: Branch, _history: &Self::History) -> Option<f64> {
        None
    }

    /// Whether a contact with this history is separated at every negative overlap and keeps the history
    /// there unchanged, as a pair that never touched does. The bed's force loop then skips the pair while
    /// it is beyond reach with no tangential spring: evaluating it would change nothing. `false` (always
    /// evaluate) unless a law says otherwise.
    fn rests_apart(&self, _history: &Self::History) -> bool {
        false
    }
}

/// What a law says about itself beyond its force, for the table (`law_table!`): its options, how a pair
/// builds it, which tangential stiffness goes with it, and its damping factor after yield.
pub trait LawInfo: NormalLaw + Sized {
    /// The law's own scene keys as a typed group (`scene_options!`), declared beside the law;
    /// `scene::NoOptions` for a law without any.
    type Options: Options + std::fmt::Debug + Clone + PartialEq;
    /// The tangential stiffness model of the law (`tangential::TangentialStiffness`).
    const TANGENTIAL: TangentialModel = TangentialModel::Ratio;
    /// beta of 000 Eq. 26 after yield when the scene gives none; `None`: the one before yield (004 Eq. 4.25).
    const PLASTIC_DAMPING_FACTOR: Option<f64> = None;
    /// The law of a contact pair (R*, m*, E*, G*, p_y, Gamma) under the laws' options (its own, the
    /// shared stiffnesses, and, for a law built on another's, that one's), its parameters derived and
    /// checked; an error names the parameter.
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<Self, ParamError>;
}

/// Defines `AnyLaw`, `AnyHistory` and their dispatch from the rows of `law_table!`.
macro_rules! define_any_law {
    ($d:tt; $($variant:ident, $module:ident, $ty:ty, $pl:literal;)*) => {
        /// The laws' options: the stiffnesses several laws share (`params::StiffnessOptions`), then each
        /// law's own (`LawInfo::Options`), one field per line of the table, named by its module.
        #[derive(Debug, Clone, PartialEq)]
        pub struct LawOptions {
            /// The stiffnesses several laws share (`elastic_stiffness`, `plastic_stiffness` and the
            /// measured unloading line).
            pub stiffness: params::StiffnessOptions,
            $(
            /// One law's own options (`LawInfo::Options`); the field is named by the law's module.
            pub $module: <$ty as LawInfo>::Options,
            )*
        }

        impl Options for LawOptions {
            const OWN_KEYS: &'static [Key] = &[];

            fn keys(out: &mut Vec<Key>) {
                params::StiffnessOptions::keys(out);
                $(<$ty as LawInfo>::Options::keys(out);)*
            }

            fn defaults() -> LawOptions {
                LawOptions { stiffness: params::StiffnessOptions::defaults(), $($module: <$ty as LawInfo>::Options::defaults(),)* }
            }

            fn read(&mut self, map: &Map<String, Value>) -> Result<(), ParamError> {
                self.stiffness.read(map)?;
                $(self.$module.read(map)?;)*
                Ok(())
            }

            fn check(&self) -> Result<(), ParamError> {
                self.stiffness.check()?;
                $(self.$module.check()?;)*
                Ok(())
            }
        }

        /// Any of the laws, chosen at run time from a scene. Dispatch is one `match`.
        #[derive(Debug, Clone, PartialEq)]
        pub enum AnyLaw {
            $(
            /// The law of one row of `law_table!`, with its parameters.
            $variant($ty),
            )*
        }

        /// The history of any law.
        #[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
        pub enum AnyHistory {
            $(
            /// The history of the law of the same name in `AnyLaw`.
            $variant(<$ty as NormalLaw>::History),
            )*
        }

        impl AnyLaw {
            /// Builds the law `model` for a pair of effective properties (R*, m*, E*, G*, p_y, Gamma)
            /// under the laws' options. The bed mixes each pair of species into one (`bed::interaction`).
            pub fn from_pair(model: ModelKind, pair: &Effective, options: &LawOptions) -> Result<AnyLaw, ParamError> {
                Ok(match model {
                    $(ModelKind::$variant => AnyLaw::$variant(<$ty as LawInfo>::from_pair(pair, options)?),)*
                })
            }

            /// Which law this is.
            pub fn model(&self) -> ModelKind {
                match self {
                    $(AnyLaw::$variant(_) => ModelKind::$variant,)*
                }
            }
        }

        impl ModelKind {
            /// The tangential stiffness model of the law (`LawInfo::TANGENTIAL`).
            pub fn tangential_model(self) -> TangentialModel {
                match self {
                    $(ModelKind::$variant => <$ty as LawInfo>::TANGENTIAL,)*
                }
            }

            /// The law's damping factor after yield when the scene gives none (`LawInfo::PLASTIC_DAMPING_FACTOR`).
            pub fn plastic_damping_factor(self) -> Option<f64> {
                match self {
                    $(ModelKind::$variant => <$ty as LawInfo>::PLASTIC_DAMPING_FACTOR,)*
                }
            }
        }

        /// Dispatches one method call to the law inside `AnyLaw`, checking the history variant matches.
        macro_rules! dispatch {
            ($d self_:ident, $d h:ident, $d law:ident, $d hist:ident => $d body:expr, $d wrap:expr, $d mismatch:expr) => {
                match ($d self_, $d h) {
                    $((AnyLaw::$variant($d law), AnyHistory::$variant($d hist)) => $d wrap(AnyHistory::$variant, $d body),)*
                    _ => {
                        // A history of another law is a programming error (restored states are checked
                        // by `Contact::remember`): loud with debug assertions, a fresh history without
                        // (the library's tests run without them: Cargo.toml).
                        debug_assert!(false, "a history of another law than {:?}", $d self_.model());
                        $d mismatch
                    }
                }
            };
        }

        fn initial_history_of(law: &AnyLaw) -> AnyHistory {
            match law {
                $(AnyLaw::$variant(l) => AnyHistory::$variant(l.initial_history()),)*
            }
        }
    };
}

crate::law_table!(define_any_law; $);

impl AnyLaw {
    /// Whether every branch is a straight line in the overlap for a fixed history (the laws the `exact`
    /// integrator solves in closed form; the table's column).
    pub fn is_piecewise_linear(&self) -> bool {
        self.model().is_piecewise_linear()
    }
}

fn wrap_eval<H>(f: fn(H) -> AnyHistory, e: Evaluation<H>) -> Evaluation<AnyHistory> {
    Evaluation { force: e.force, stiffness: e.stiffness, branch: e.branch, lower: e.lower, upper: e.upper, history: f(e.history) }
}

fn plain<H, T>(_: fn(H) -> AnyHistory, v: T) -> T {
    v
}

impl NormalLaw for AnyLaw {
    type History = AnyHistory;

    fn initial_history(&self) -> AnyHistory {
        initial_history_of(self)
    }

    /// A history of another law is a programming error; it is answered with the law's own initial
    /// history rather than a panic.
    fn evaluate(&self, alpha: f64, history: &AnyHistory) -> Evaluation<AnyHistory> {
        dispatch!(self, history, l, h => l.evaluate(alpha, h), wrap_eval, self.evaluate(alpha, &self.initial_history()))
    }

    fn has_yielded(&self, history: &AnyHistory) -> bool {
        dispatch!(self, history, l, h => l.has_yielded(h), plain, false)
    }

    fn sliding_normal_force(&self, force: f64, alpha: f64, history: &AnyHistory) -> f64 {
        dispatch!(self, history, l, h => l.sliding_normal_force(force, alpha, h), plain, force)
    }

    fn pull_off_force(&self, history: &AnyHistory) -> f64 {
        dispatch!(self, history, l, h => l.pull_off_force(h), plain, 0.0)
    }

    fn plastic_overlap(&self, history: &AnyHistory) -> f64 {
        dispatch!(self, history, l, h => l.plastic_overlap(h), plain, 0.0)
    }

    fn contact_radius(&self, alpha: f64, history: &AnyHistory) -> Option<f64> {
        dispatch!(self, history, l, h => l.contact_radius(alpha, h), plain, None)
    }

    fn damping_stiffness(&self, alpha: f64, history: &AnyHistory, branch_stiffness: f64) -> f64 {
        dispatch!(self, history, l, h => l.damping_stiffness(alpha, h, branch_stiffness), plain, branch_stiffness.abs())
    }

    fn mindlin_radius(&self, alpha: f64, history: &AnyHistory, contact_radius: Option<f64>) -> Option<f64> {
        dispatch!(self, history, l, h => l.mindlin_radius(alpha, h, contact_radius), plain, contact_radius)
    }

    fn vertical_end(&self, branch: Branch, history: &AnyHistory) -> Option<f64> {
        dispatch!(self, history, l, h => l.vertical_end(branch, h), plain, None)
    }

    fn rests_apart(&self, history: &AnyHistory) -> bool {
        dispatch!(self, history, l, h => l.rests_apart(h), plain, false)
    }
}
