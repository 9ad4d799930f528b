//! The registries of the plants and gravity fields the engine is compiled for, each listed
//! once. (The laws' registry is at the end of [`crate::control`].)
//!
//! A plant type is a monomorphised rollout per instruction-set level, so the list is also the
//! list of what gets compiled: [`AnyPlant::visit`] is the one place that dispatches on it. A
//! table's `kind` picks the entry ([`PlantCase::from_params`]); for the small body the nested
//! gravity field's kind, and for the tethered satellite its fidelity and node count, pick the
//! type too.

use nalgebra::Vector3;

use crate::batch::PerCase;
use crate::error::{ParamError, Validate};
use crate::gravity::{GravityField, Harmonic2, PointMass, TwoPointMass};
use crate::params::{FromParams, ParamSource};
use crate::plant::tether::{
    NODE_COUNTS, TetheredFlexible2, TetheredFlexible4, TetheredFlexible8, TetheredFlexible16,
    TetheredSimplified,
};
use crate::plant::{DoubleIntegrator, MarsLander, PlantModel, SmallBody};

/// Something to do with a batch's plants, whatever their type.
pub trait PlantVisitor {
    type Output;
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output;
}

/// Lists each compiled plant type once: generates [`PlantCase`], [`AnyPlant`] and their
/// dispatch.
macro_rules! plants {
    ($($variant:ident($ty:ty) = $d:literal,)*) => {
        /// One case's plant, of any registered type.
        #[derive(Clone, Debug, PartialEq)]
        pub enum PlantCase {
            $($variant($ty),)*
        }

        /// A batch's plants (one shared, or one per case), all of one registered type.
        #[derive(Clone, Debug)]
        pub enum AnyPlant {
            $($variant(PerCase<$ty>),)*
        }

        impl PlantCase {
            fn validate(&self) -> Result<(), ParamError> {
                match self {
                    $(Self::$variant(p) => p.validate(),)*
                }
            }

            fn variant(&self) -> &'static str {
                match self {
                    $(Self::$variant(_) => stringify!($variant),)*
                }
            }
        }

        impl AnyPlant {
            /// The plants of the cases (one case: shared by every case of a batch).
            pub fn from_cases(cases: Vec<PlantCase>) -> Result<Self, PlantMismatch> {
                let first = cases.first().ok_or(PlantMismatch { case: 0 })?.variant();
                if let Some(case) = cases.iter().position(|c| c.variant() != first) {
                    return Err(PlantMismatch { case });
                }
                Ok(match &cases[0] {
                    $(PlantCase::$variant(_) => Self::$variant(PerCase::from_vec(
                        cases
                            .into_iter()
                            .map(|c| match c {
                                PlantCase::$variant(p) => p,
                                _ => unreachable!("checked above"),
                            })
                            .collect(),
                    )),)*
                })
            }

            /// Calls the visitor with the typed plants.
            pub fn visit<V: PlantVisitor>(&self, v: V) -> V::Output {
                match self {
                    $(Self::$variant(p) => v.visit::<$d, $ty>(p),)*
                }
            }

            /// Number of generalized coordinates.
            pub fn axes(&self) -> usize {
                match self {
                    $(Self::$variant(_) => $d,)*
                }
            }

            /// Number of plant values held (1 when shared).
            pub fn len(&self) -> usize {
                match self {
                    $(Self::$variant(p) => p.len(),)*
                }
            }

            pub fn is_empty(&self) -> bool {
                self.len() == 0
            }
        }
    };
}

plants! {
    Mars(MarsLander) = 3,
    DoubleIntegrator(DoubleIntegrator) = 3,
    SmallBodyPointMass(SmallBody<PointMass>) = 3,
    SmallBodyTwoPointMass(SmallBody<TwoPointMass>) = 3,
    SmallBodyHarmonic2(SmallBody<Harmonic2>) = 3,
    TetherSimplified(TetheredSimplified) = 2,
    TetherFlexible2(TetheredFlexible2) = 2,
    TetherFlexible4(TetheredFlexible4) = 2,
    TetherFlexible8(TetheredFlexible8) = 2,
    TetherFlexible16(TetheredFlexible16) = 2,
}

/// Cases whose plants are of different types (e.g. per-case node counts).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlantMismatch {
    pub case: usize,
}

/// The plant kinds at the Python boundary.
pub const PLANT_KINDS: [&str; 4] = [
    "mars_lander",
    "double_integrator",
    "small_body",
    "tethered_satellite",
];

/// The tethered satellite's fidelities.
pub const TETHER_FIDELITIES: [&str; 2] = ["simplified", "flexible"];

impl PlantCase {
    /// The plant a table describes, validated: its `kind`, and for a small body its gravity
    /// field's kind, for a tethered satellite its fidelity and node count, pick the type.
    pub fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, S::Error> {
        let case = match PLANT_KINDS[p.kind(&PLANT_KINDS)?] {
            "mars_lander" => Self::Mars(MarsLander::from_params(p)?),
            "double_integrator" => Self::DoubleIntegrator(DoubleIntegrator::from_params(p)?),
            "small_body" => match GRAVITY_KINDS[p.nested("gravity", |g| g.kind(&GRAVITY_KINDS))?] {
                "point_mass" => Self::SmallBodyPointMass(SmallBody::from_params(p)?),
                "two_point_mass" => Self::SmallBodyTwoPointMass(SmallBody::from_params(p)?),
                _ => Self::SmallBodyHarmonic2(SmallBody::from_params(p)?),
            },
            _ => match TETHER_FIDELITIES[p.choice("fidelity", &TETHER_FIDELITIES)?] {
                "simplified" => Self::TetherSimplified(TetheredSimplified::from_params(p)?),
                _ => match p.count("nodes", &NODE_COUNTS, "nodes in {2, 4, 8, 16}")? {
                    2 => Self::TetherFlexible2(FromParams::from_params(p)?),
                    4 => Self::TetherFlexible4(FromParams::from_params(p)?),
                    8 => Self::TetherFlexible8(FromParams::from_params(p)?),
                    _ => Self::TetherFlexible16(FromParams::from_params(p)?),
                },
            },
        };
        case.validate()?;
        Ok(case)
    }
}

/// Lists each gravity field once: generates [`AnyGravity`] and [`GRAVITY_KINDS`].
macro_rules! gravities {
    ($($variant:ident => $kind:literal,)*) => {
        /// A gravity field of any registered type (one case's).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum AnyGravity {
            $($variant($variant),)*
        }

        /// The gravity fields' kinds at the Python boundary.
        pub const GRAVITY_KINDS: [&str; [$($kind),*].len()] = [$($kind),*];

        impl AnyGravity {
            /// The field a table describes, validated.
            pub fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, S::Error> {
                let field = match GRAVITY_KINDS[p.kind(&GRAVITY_KINDS)?] {
                    $($kind => Self::$variant($variant::from_params(p)?),)*
                    _ => unreachable!("kind() returns a registered kind"),
                };
                match &field {
                    $(Self::$variant(g) => g.validate()?,)*
                }
                Ok(field)
            }

            /// The field's kind at the Python boundary.
            pub fn kind(&self) -> &'static str {
                match self {
                    $(Self::$variant(_) => $kind,)*
                }
            }

            /// Field at `r`, m/s^2.
            pub fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64> {
                match self {
                    $(Self::$variant(g) => g.acceleration(r),)*
                }
            }

            /// Potential at `r`, m^2/s^2.
            pub fn potential(&self, r: &Vector3<f64>) -> f64 {
                match self {
                    $(Self::$variant(g) => g.potential(r),)*
                }
            }
        }
    };
}

gravities! {
    PointMass => "point_mass",
    TwoPointMass => "two_point_mass",
    Harmonic2 => "harmonic2",
}
