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

use nalgebra::{SVector, Vector3};

use crate::batch::PerCase;
use crate::control::LawKind;
use crate::dispersion::DispersionKind;
use crate::disturbance::ComponentKind;
use crate::error::{ParamError, ReadError, Validate};
use crate::fuzzy::{Mamdani, MembershipShape};
use crate::gravity::{GravityField, Harmonic2, PointMass, TwoPointMass};
use crate::navigation::{FilterKind, SensorKind};
use crate::params::{
    AxisCount, Cases, Declared, Dim, FromParams, Kinds, ParamSource, Schema, Table,
};
use crate::plant::small_body::{GRAVITY, SMALL_BODY};
use crate::plant::tether::{
    FIDELITY, Fidelity, NODES, NodeCount, TETHERED_SATELLITE, TetheredFlexible2, TetheredFlexible4,
    TetheredFlexible8, TetheredFlexible16, TetheredSimplified,
};
use crate::plant::{DoubleIntegrator, MarsLander, Plant, PlantModel, SmallBody};
use crate::reference::ReferenceKind;
use crate::state::State;

/// Something to do with a batch's plants, whatever their type.
pub trait PlantVisitor {
    type Output;
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output
    where
        Dim<D>: AxisCount<D>;
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
            /// The plant kinds at the Python boundary, and their schemas.
            pub enum PlantKind in "plant" {
                $($kind => $name: <$ty as Declared>::SCHEMA,)*
                $($fkind => $fname: <$fcase as Declared>::SCHEMA,)*
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
            pub fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
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

/// What a batch's plants are: their state and command names, axes, derived figures (of the
/// first case) and the largest stable step over the cases.
#[derive(Clone, Debug, PartialEq)]
pub struct PlantInfo {
    pub state_names: &'static [&'static str],
    pub control_names: &'static [&'static str],
    pub axes: usize,
    pub figures: Vec<(&'static str, Vec<f64>)>,
    pub max_step: f64,
}

struct Describe;

impl PlantVisitor for Describe {
    type Output = PlantInfo;
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> PlantInfo {
        PlantInfo {
            state_names: P::STATE_NAMES,
            control_names: P::CONTROL_NAMES,
            axes: D,
            figures: plants.get(0).figures(),
            // the smallest step over the cases, so one integrator step serves the whole batch
            max_step: plants
                .iter()
                .map(|p| p.max_step())
                .fold(f64::INFINITY, f64::min),
        }
    }
}

/// The coordinates (q, q') of rows of states.
struct Coordinates<'a>(&'a [f64]);

impl PlantVisitor for Coordinates<'_> {
    type Output = (Vec<f64>, Vec<f64>);
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output {
        let rows = self.0.len() / P::STATE_DIM;
        let (mut q, mut qd) = (Vec::with_capacity(rows * D), Vec::with_capacity(rows * D));
        for row in self.0.chunks_exact(P::STATE_DIM) {
            let x = <P as Plant<f64, D>>::State::from_components(|i| row[i]);
            let (a, b) = plants.get(0).coordinates(&x);
            q.extend_from_slice(a.as_slice());
            qd.extend_from_slice(b.as_slice());
        }
        (q, qd)
    }
}

/// States from rows of (q, q').
struct StatesAt<'a>(&'a [f64]);

impl PlantVisitor for StatesAt<'_> {
    type Output = Result<Vec<f64>, ReadError>;
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output {
        let n = self.0.len() / (2 * D);
        if plants.len() != 1 && plants.len() != n {
            return Err(ReadError::value(format!(
                "the plant has {} cases and the coordinates {n} rows",
                plants.len()
            )));
        }
        let mut out = Vec::with_capacity(n * P::STATE_DIM);
        for (i, r) in self.0.chunks_exact(2 * D).enumerate() {
            if let Some(v) = r.iter().find(|v| !v.is_finite()) {
                return Err(ReadError::value(format!(
                    "coordinates[{i}] = {v} violates finite values"
                )));
            }
            let q = SVector::<f64, D>::from_column_slice(&r[..D]);
            let qd = SVector::<f64, D>::from_column_slice(&r[D..]);
            let x = plants.get(i).state_at(&q, &qd).ok_or_else(|| {
                ReadError::value("this plant's state is not determined by its coordinates")
            })?;
            let x = x.map_err(|e| ReadError::from(e).context(&format!("row {i}")))?;
            if x.iter().any(|v| !v.is_finite()) {
                return Err(ReadError::value(format!(
                    "coordinates[{i}] = {r:?} violates coordinates that give a finite state (angles and rates too large)"
                )));
            }
            out.extend(x)
        }
        Ok(out)
    }
}

/// The initial states of a batch of `plants`: rows of `x0` (one per case), each checked by
/// its case's plant.
pub fn initial_states<const D: usize, P: PlantModel<D>>(
    plants: &PerCase<P>,
    x0: &[f64],
) -> Result<Vec<<P as Plant<f64, D>>::State>, ReadError> {
    x0.chunks_exact(P::STATE_DIM)
        .enumerate()
        .map(|(i, row)| {
            plants.get(i).check_initial(row).map_err(|e| {
                let axis = e.axis.unwrap_or(0);
                ReadError::value(format!("x0[{i}, {axis}] = {} violates {}", e.value, e.rule))
            })?;
            Ok(<P as Plant<f64, D>>::State::from_components(|c| row[c]))
        })
        .collect()
}

impl AnyPlant {
    /// The plants a table describes, one per case or one for all, with what the cases turned
    /// out to be.
    pub fn from_table(table: &Table) -> Result<(Self, Cases), ReadError> {
        let (cases, found) = table.read_cases(None, |p| PlantCase::from_params(p))?;
        let plants = Self::from_cases(cases.iter().cloned().collect()).map_err(|m| {
            ReadError::value(format!(
                "case {} has another plant type than case 0 (nodes or the gravity field's kind differ)",
                m.case
            ))
        })?;
        Ok((plants, found))
    }

    /// Names, axes, figures and the largest stable step.
    pub fn info(&self) -> PlantInfo {
        self.visit(Describe)
    }

    /// The generalized coordinates (q, q') the laws read, each row-major (rows x axes), of
    /// states given as rows of `width` components.
    pub fn coordinates(
        &self,
        states: &[f64],
        width: usize,
    ) -> Result<(Vec<f64>, Vec<f64>), ReadError> {
        let names = self.info().state_names;
        if width != names.len() {
            return Err(ReadError::value(format!(
                "states have {width} components; this plant's have {} ({names:?})",
                names.len()
            )));
        }
        Ok(self.visit(Coordinates(states)))
    }

    /// States (rows x state dim, row-major) at `[n, width]` rows of (q, q'), for the plants
    /// whose state they determine (the tethered satellite).
    pub fn states_at(&self, rows: &[f64], [n, width]: [usize; 2]) -> Result<Vec<f64>, ReadError> {
        let axes = self.axes();
        if width != 2 * axes {
            return Err(ReadError::value(format!(
                "coordinates have shape ({n}, {width}); give (M, {}): q then q'",
                2 * axes
            )));
        }
        self.visit(StatesAt(rows))
    }
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

impl Declared for TetherCase {
    const SCHEMA: Schema = Schema::new(TETHERED_SATELLITE);
}

impl FromParams for TetherCase {
    /// `fidelity` picks the model, and for the flexible tether `nodes` its state size.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(match p.choice::<Fidelity>(&FIDELITY)? {
            Fidelity::Simplified => Self::Simplified(TetheredSimplified::from_params(p)?),
            Fidelity::Flexible => match p.count_of::<NodeCount>(&NODES)? {
                NodeCount::N2 => Self::Flexible2(FromParams::from_params(p)?),
                NodeCount::N4 => Self::Flexible4(FromParams::from_params(p)?),
                NodeCount::N8 => Self::Flexible8(FromParams::from_params(p)?),
                NodeCount::N16 => Self::Flexible16(FromParams::from_params(p)?),
            },
        })
    }
}

/// Lists each gravity field once, with its name at the Python boundary: generates
/// [`GravityKind`], [`GRAVITY_KINDS`], [`AnyGravity`], and the small body's family of plants,
/// one per field ([`SmallBodyCase`], [`SmallBodies`]).
macro_rules! gravities {
    ($($variant:ident => $kind:literal,)*) => {
        crate::named! {
            /// The gravity fields' kinds at the Python boundary, and their schemas.
            pub enum GravityKind in "gravity" {
                $($variant => $kind: <$variant as Declared>::SCHEMA,)*
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
            pub fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
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

            /// The acceleration (3 values per position) or the potential (1) at positions
            /// given as `[n, width]` rows, refusing another width than 3 and non-finite
            /// coordinates by their position.
            pub fn evaluate(&self, r: &[f64], [n, width]: [usize; 2], potential: bool) -> Result<Vec<f64>, ReadError> {
                if width != 3 {
                    return Err(ReadError::value(format!(
                        "r has shape ({n}, {width}); it takes (3,) or (N, 3)"
                    )));
                }
                if let Some((k, v)) = r.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                    return Err(ReadError::value(format!(
                        "r[{}, {}] = {v} violates finite values",
                        k / 3,
                        k % 3
                    )));
                }
                let mut out = Vec::with_capacity(if potential { r.len() / 3 } else { r.len() });
                for row in r.chunks_exact(3) {
                    let x = Vector3::new(row[0], row[1], row[2]);
                    if potential {
                        out.push(self.potential(&x));
                    } else {
                        out.extend_from_slice(self.acceleration(&x).as_slice());
                    }
                }
                Ok(out)
            }
        }

        compiled! {
            /// A small body, with any registered gravity field.
            SmallBodyCase, SmallBodies {
                $($variant(SmallBody<$variant>) = 3,)*
            }
        }

        impl Declared for SmallBodyCase {
            const SCHEMA: Schema = Schema::new(SMALL_BODY);
        }

        impl FromParams for SmallBodyCase {
            /// The nested field's kind picks the type.
            fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
                Ok(match p.nested(&GRAVITY, |g| g.kind::<GravityKind>())? {
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

/// Every family's kinds with what they declare, for the bindings' schema: the plants, the laws,
/// the gravity fields, the disturbance components, the references, the dispersions and the
/// fuzzy system's table (the system, then its membership shapes).
pub fn schemas() -> Vec<(&'static str, Vec<(&'static str, Schema)>)> {
    fn family<K: Kinds>() -> (&'static str, Vec<(&'static str, Schema)>) {
        (
            K::FAMILY,
            K::ALL.iter().map(|k| (k.name(), k.schema())).collect(),
        )
    }
    let mut fuzzy = family::<MembershipShape>();
    fuzzy
        .1
        .insert(0, ("mamdani", <Mamdani as Declared>::SCHEMA));
    vec![
        family::<PlantKind>(),
        family::<LawKind>(),
        family::<GravityKind>(),
        family::<ComponentKind>(),
        family::<ReferenceKind>(),
        family::<DispersionKind>(),
        family::<SensorKind>(),
        family::<FilterKind>(),
        fuzzy,
    ]
}
