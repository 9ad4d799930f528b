//! Parameter descriptors: every parameter of every model is declared once, as a [`Param`]
//! constant beside the model (its name, shape, unit, rule and a line of documentation). The
//! model reads its table through the descriptors (`p.axes(&B1)`), its validator names the
//! descriptor's parameter and rule in its errors, and the bindings expose the declarations as
//! the schema (`landing._core.SCHEMAS`).

/// How a parameter's values are laid out in its table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A number: shared by every case, or one per case.
    Scalar,
    /// A number per axis (one number serves every axis): shared, or per case.
    PerAxis,
    /// A number per component (of a dispersion, of a fuzzy set's corners, of a sensor's
    /// `[q, q']`): a single number serves every component. Shared by every case, unless the
    /// parameter is declared [`Param::per_case`] (a sensor's).
    PerComponent,
    /// One of these names, shared by every case.
    Choice(&'static [&'static str]),
    /// True or false, shared by every case.
    Flag,
    /// A whole number among these, shared by every case (it fixes a size or a type).
    Count(&'static [usize]),
    /// A table of its own.
    Nested(Layout),
    /// A list of tables.
    List(Layout),
    /// A compiled fuzzy inference system (a `landing.fuzzy.Mamdani`), shared by every case.
    FuzzySystem,
}

/// What a nested table (or each table of a list) holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Layout {
    /// One of the kinds of this family (the table's `kind` says which).
    Family(&'static str),
    /// These parameters.
    Fixed(&'static [Param]),
}

impl Shape {
    /// The shape's name in the schema.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Scalar => "scalar",
            Shape::PerAxis => "per_axis",
            Shape::PerComponent => "per_component",
            Shape::Choice(_) => "choice",
            Shape::Flag => "flag",
            Shape::Count(_) => "count",
            Shape::Nested(_) => "nested",
            Shape::List(_) => "list",
            Shape::FuzzySystem => "fuzzy_system",
        }
    }

    /// Whether the parameter is numbers a case reads (a scalar or per axis).
    pub fn is_numeric(&self) -> bool {
        matches!(self, Shape::Scalar | Shape::PerAxis)
    }
}

/// One parameter as a table gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Param {
    /// The key, as the user spells it (the Python keyword).
    pub name: &'static str,
    pub shape: Shape,
    /// SI unit ("1" for a dimensionless number, "" for one that is not a number).
    pub unit: &'static str,
    /// The rule the validator enforces, written as an inequality ("" if only finiteness).
    pub rule: &'static str,
    /// A second rule checked on its own ("" if none), e.g. `side < tether_length`.
    pub also: &'static str,
    /// Whether the table must give it (an optional parameter may be absent or None).
    pub required: bool,
    /// Whether a per-component parameter may be given per case, `(N, K)` or `(N, 1)`
    /// ([`Param::per_case`]); scalars and per-axis parameters always may.
    pub case_rows: bool,
    /// One line of documentation.
    pub doc: &'static str,
}

impl Param {
    pub const fn new(name: &'static str, shape: Shape) -> Self {
        Self {
            name,
            shape,
            unit: "",
            rule: "",
            also: "",
            required: true,
            case_rows: false,
            doc: "",
        }
    }

    pub const fn scalar(name: &'static str) -> Self {
        Self::new(name, Shape::Scalar)
    }

    pub const fn axes(name: &'static str) -> Self {
        Self::new(name, Shape::PerAxis)
    }

    pub const fn components(name: &'static str) -> Self {
        Self::new(name, Shape::PerComponent)
    }

    pub const fn choice(name: &'static str, names: &'static [&'static str]) -> Self {
        Self::new(name, Shape::Choice(names))
    }

    pub const fn flag(name: &'static str) -> Self {
        Self::new(name, Shape::Flag)
    }

    pub const fn count(name: &'static str, allowed: &'static [usize]) -> Self {
        Self::new(name, Shape::Count(allowed))
    }

    pub const fn nested(name: &'static str, layout: Layout) -> Self {
        Self::new(name, Shape::Nested(layout))
    }

    pub const fn list(name: &'static str, layout: Layout) -> Self {
        Self::new(name, Shape::List(layout))
    }

    pub const fn fuzzy_system(name: &'static str) -> Self {
        Self::new(name, Shape::FuzzySystem)
    }

    pub const fn unit(self, unit: &'static str) -> Self {
        Self { unit, ..self }
    }

    pub const fn rule(self, rule: &'static str) -> Self {
        Self { rule, ..self }
    }

    pub const fn also(self, also: &'static str) -> Self {
        Self { also, ..self }
    }

    pub const fn optional(self) -> Self {
        Self {
            required: false,
            ..self
        }
    }

    pub const fn doc(self, doc: &'static str) -> Self {
        Self { doc, ..self }
    }

    /// A per-component parameter its model reads per case ([`ParamSource::case_components`]).
    ///
    /// [`ParamSource::case_components`]: crate::params::ParamSource::case_components
    pub const fn per_case(self) -> Self {
        Self {
            case_rows: true,
            ..self
        }
    }

    /// Whether the parameter may be given one row per case (the numbers a case reads).
    pub fn varies_by_case(&self) -> bool {
        self.shape.is_numeric() || (self.shape == Shape::PerComponent && self.case_rows)
    }

    /// Every rule of the parameter, as the schema states it.
    pub fn rules(&self) -> String {
        match (self.rule, self.also) {
            (r, "") => r.to_string(),
            ("", a) => a.to_string(),
            (r, a) => format!("{r}, {a}"),
        }
    }
}

/// What a kind of model declares: its parameters (in the order the Python layer lists them)
/// and, for a disturbance component, whether it draws random numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schema {
    pub params: &'static [Param],
    pub random: Option<bool>,
}

impl Schema {
    pub const fn new(params: &'static [Param]) -> Self {
        Self {
            params,
            random: None,
        }
    }

    /// A disturbance component's schema: `random` if it draws random numbers.
    pub const fn component(params: &'static [Param], random: bool) -> Self {
        Self {
            params,
            random: Some(random),
        }
    }

    /// The parameter named `name`, if declared.
    pub fn param(&self, name: &str) -> Option<&'static Param> {
        self.params.iter().find(|p| p.name == name)
    }
}

/// A model type that reads its parameters from a table: what it declares.
pub trait Declared {
    const SCHEMA: Schema;
}
