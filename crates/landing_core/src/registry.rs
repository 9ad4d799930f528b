//! The registries of the plants and gravity fields the engine is compiled for, each kind listed
//! once. (The laws' registry is at the end of [`crate::control`].)
//!
//! A plant type is a monomorphised rollout per instruction-set level, so the lists are also the
//! list of what gets compiled: [`AnyPlant::visit`] is the one place that dispatches on it. A
//! table's `kind` picks the entry ([`PlantCase::from_params`]). A kind is one compiled type
//! (the Mars lander) or a family of them that further parameters pick: for the small body the
//! nested gravity field's kind (the family is generated from [`gravities!`], so a new field is
//! one line there), for the tethered satellite its fidelity and node count. Every choice is a
//! `match` over a [`Named`](crate::params::Named) or [`Counted`](crate::params::Counted) enum
//! that names each variant: a kind added to a list and forgotten in a `match` is a compile
//! error.

use nalgebra::Vector3;

use crate::batch::PerCase;
use crate::error::{ParamError, Validate};
use crate::gravity::{GravityField, Harmonic2, PointMass, TwoPointMass};
use crate::params::{FromParams, ParamSource};
use crate::plant::tether::{
    Fidelity, NodeCount, TetheredFlexible2, TetheredFlexible4, TetheredFlexible8,
    TetheredFlexible16, TetheredSimplified,
};
use crate::plant::{DoubleIntegrator, MarsLander, PlantModel, SmallBody};

/// Something to do with a batch's plants, whatever their type.
pub trait PlantVisitor {
    type Output;
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output;
}

/// Cases whose plants are of different types (e.g. per-case node counts).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlantMismatch {
    pub case: usize,
}

/// A family of compiled plant types behind one kind: `$case` holds one case's plant,
/// `$batch` a batch's plants of one of the types.
macro_rules! compiled {
    ($(#[$meta:meta])* $case:ident, $batch:ident { $($variant:ident($ty:ty) = $d:literal,)* }) => {
        $(#[$meta])*
        #[derive(Clone, Debug, PartialEq)]
        pub enum $case {
            $($variant($ty),)*
        }

        /// A batch's plants (one shared, or one per case), all of one type of the family.
        #[derive(Clone, Debug)]
        pub enum $batch {
            $($variant(PerCase<$ty>),)*
        }

        impl $case {
            fn validate(&self) -> Result<(), ParamError> {
                match self {
                    $(Self::$variant(p) => p.validate(),)*
                }
            }

            fn same_type(&self, other: &Self) -> bool {
                matches!((self, other), $((Self::$variant(_), Self::$variant(_)))|*)
            }
        }

        impl $batch {
            /// The plants of cases of one type (checked by the caller).
            fn of(cases: Vec<$case>) -> Self {
                match &cases[0] {
                    $($case::$variant(_) => Self::$variant(PerCase::from_vec(
                        cases
                            .into_iter()
                            .map(|c| match c {
                                $case::$variant(p) => p,
                                _ => unreachable!("the cases have one type"),
                            })
                            .collect(),
                    )),)*
                }
            }

            fn visit<V: PlantVisitor>(&self, v: V) -> V::Output {
                match self {
                    $(Self::$variant(p) => v.visit::<$d, $ty>(p),)*
                }
            }

            fn axes(&self) -> usize {
                match self {
                    $(Self::$variant(_) => $d,)*
                }
            }

            fn len(&self) -> usize {
                match self {
                    $(Self::$variant(p) => p.len(),)*
                }
            }
        }
    };
}

/// Lists each plant kind once, with its name at the Python boundary: first the kinds of one
/// compiled type (`Kind => "name": Variant(Type) = axes`), then the families
/// (`Kind => "name": Variant(Case, Batch)`, made by `compiled!`). Generates [`PlantKind`],
/// [`PLANT_KINDS`], [`PlantCase`], [`AnyPlant`], their parsing and their dispatch.
macro_rules! plants {
    (
        $($kind:ident => $name:literal: $variant:ident($ty:ty) = $d:literal,)*;
        $($fkind:ident => $fname:literal: $fvariant:ident($fcase:ty, $fbatch:ty),)*
    ) => {
        crate::named! {
            /// The plant kinds at the Python boundary.
            pub enum PlantKind {
                $($kind => $name,)*
                $($fkind => $fname,)*
            }
        }

        /// The plant kinds' names.
        pub const PLANT_KINDS: &[&str] = PlantKind::NAMES;

        /// One case's plant, of any registered type.
        #[derive(Clone, Debug, PartialEq)]
        pub enum PlantCase {
            $($variant($ty),)*
            $($fvariant($fcase),)*
        }

        /// A batch's plants (one shared, or one per case), all of one registered type.
        #[derive(Clone, Debug)]
        pub enum AnyPlant {
            $($variant(PerCase<$ty>),)*
            $($fvariant($fbatch),)*
        }

        impl PlantCase {
            /// The plant a table describes, validated: its `kind` picks the entry, and within
            /// a family the parameters that pick the type.
            pub fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, S::Error> {
                let case = match p.kind::<PlantKind>()? {
                    $(PlantKind::$kind => Self::$variant(<$ty>::from_params(p)?),)*
                    $(PlantKind::$fkind => Self::$fvariant(<$fcase>::from_params(p)?),)*
                };
                case.validate()?;
                Ok(case)
            }

            fn validate(&self) -> Result<(), ParamError> {
                match self {
                    $(Self::$variant(p) => p.validate(),)*
                    $(Self::$fvariant(f) => f.validate(),)*
                }
            }

            fn same_type(&self, other: &Self) -> bool {
                match (self, other) {
                    $((Self::$variant(_), Self::$variant(_)) => true,)*
                    $((Self::$fvariant(a), Self::$fvariant(b)) => a.same_type(b),)*
                    _ => false,
                }
            }
        }

        impl AnyPlant {
            /// The plants of the cases (one case: shared by every case of a batch).
            pub fn from_cases(cases: Vec<PlantCase>) -> Result<Self, PlantMismatch> {
                let first = cases.first().ok_or(PlantMismatch { case: 0 })?;
                if let Some(case) = cases.iter().position(|c| !first.same_type(c)) {
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
                    $(PlantCase::$fvariant(_) => Self::$fvariant(<$fbatch>::of(
                        cases
                            .into_iter()
                            .map(|c| match c {
                                PlantCase::$fvariant(p) => p,
                                _ => unreachable!("checked above"),
                            })
                            .collect(),
                    )),)*
                })
            }

            /// The plants' kind.
            pub fn kind(&self) -> PlantKind {
                match self {
                    $(Self::$variant(_) => PlantKind::$kind,)*
                    $(Self::$fvariant(_) => PlantKind::$fkind,)*
                }
            }

            /// Calls the visitor with the typed plants.
            pub fn visit<V: PlantVisitor>(&self, v: V) -> V::Output {
                match self {
                    $(Self::$variant(p) => v.visit::<$d, $ty>(p),)*
                    $(Self::$fvariant(b) => b.visit(v),)*
                }
            }

            /// Number of generalized coordinates.
            pub fn axes(&self) -> usize {
                match self {
                    $(Self::$variant(_) => $d,)*
                    $(Self::$fvariant(b) => b.axes(),)*
                }
            }

            /// Number of plant values held (1 when shared).
            pub fn len(&self) -> usize {
                match self {
                    $(Self::$variant(p) => p.len(),)*
                    $(Self::$fvariant(b) => b.len(),)*
                }
            }

            pub fn is_empty(&self) -> bool {
                self.len() == 0
            }
        }
    };
}

plants! {
    MarsLander => "mars_lander": Mars(MarsLander) = 3,
    DoubleIntegrator => "double_integrator": DoubleIntegrator(DoubleIntegrator) = 3,
    ;
    SmallBody => "small_body": SmallBody(SmallBodyCase, SmallBodies),
    TetheredSatellite => "tethered_satellite": Tether(TetherCase, Tethers),
}

compiled! {
    /// A tethered satellite: the rigid dumbbell, or the flexible tether at one of its node
    /// counts ([`NodeCount`]).
    TetherCase, Tethers {
        Simplified(TetheredSimplified) = 2,
        Flexible2(TetheredFlexible2) = 2,
        Flexible4(TetheredFlexible4) = 2,
        Flexible8(TetheredFlexible8) = 2,
        Flexible16(TetheredFlexible16) = 2,
    }
}

/// The tethered satellite's fidelities' names.
pub const TETHER_FIDELITIES: &[&str] = Fidelity::NAMES;

impl FromParams for TetherCase {
    /// `fidelity` picks the model, and for the flexible tether `nodes` its state size.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, S::Error> {
        Ok(match p.choice::<Fidelity>("fidelity")? {
            Fidelity::Simplified => Self::Simplified(TetheredSimplified::from_params(p)?),
            Fidelity::Flexible => {
                match p.count_of::<NodeCount>("nodes", "nodes in {2, 4, 8, 16}")? {
                    NodeCount::N2 => Self::Flexible2(FromParams::from_params(p)?),
                    NodeCount::N4 => Self::Flexible4(FromParams::from_params(p)?),
                    NodeCount::N8 => Self::Flexible8(FromParams::from_params(p)?),
                    NodeCount::N16 => Self::Flexible16(FromParams::from_params(p)?),
                }
            }
        })
    }
}

/// Lists each gravity field once, with its name at the Python boundary: generates
/// [`GravityKind`], [`GRAVITY_KINDS`], [`AnyGravity`], and the small body's family of plants,
/// one per field ([`SmallBodyCase`], [`SmallBodies`]).
macro_rules! gravities {
    ($($variant:ident => $kind:literal,)*) => {
        crate::named! {
            /// The gravity fields' kinds at the Python boundary.
            pub enum GravityKind {
                $($variant => $kind,)*
            }
        }

        /// The gravity fields' kinds' names.
        pub const GRAVITY_KINDS: &[&str] = GravityKind::NAMES;

        /// A gravity field of any registered type (one case's).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum AnyGravity {
            $($variant($variant),)*
        }

        impl AnyGravity {
            /// The field a table describes, validated.
            pub fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, S::Error> {
                let field = match p.kind::<GravityKind>()? {
                    $(GravityKind::$variant => Self::$variant($variant::from_params(p)?),)*
                };
                match &field {
                    $(Self::$variant(g) => g.validate()?,)*
                }
                Ok(field)
            }

            /// The field's kind.
            pub fn kind(&self) -> GravityKind {
                match self {
                    $(Self::$variant(_) => GravityKind::$variant,)*
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

        compiled! {
            /// A small body, with any registered gravity field.
            SmallBodyCase, SmallBodies {
                $($variant(SmallBody<$variant>) = 3,)*
            }
        }

        impl FromParams for SmallBodyCase {
            /// The nested field's kind picks the type.
            fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, S::Error> {
                Ok(match p.nested("gravity", |g| g.kind::<GravityKind>())? {
                    $(GravityKind::$variant => Self::$variant(SmallBody::from_params(p)?),)*
                })
            }
        }
    };
}

gravities! {
    PointMass => "point_mass",
    TwoPointMass => "two_point_mass",
    Harmonic2 => "harmonic2",
}
