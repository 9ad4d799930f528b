//! Closed sets of names and counts: a table's `kind`, a law's variant, a switching function, a
//! model's size. Each is an enum written once with [`named!`](crate::named), which generates its
//! list of names (or values) in declaration order; a `match` on it names every variant, so a
//! variant added to the list and forgotten in a `match` is a compile error.

/// A closed set of values named at the boundary.
pub trait Named: Copy + PartialEq + std::fmt::Debug + 'static {
    /// The names, in declaration order.
    const NAMES: &'static [&'static str];
    /// The values, in the same order.
    const ALL: &'static [Self];

    fn name(self) -> &'static str;

    /// The value named `name`, if any.
    fn from_name(name: &str) -> Option<Self> {
        Self::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Self::ALL[i])
    }
}

/// The kinds of one family of models (the laws, the plants, the gravity fields...): their
/// names, and what each kind declares.
pub trait Kinds: Named {
    /// The family's name in the schema (`"law"`, `"plant"`, ...).
    const FAMILY: &'static str;

    fn schema(self) -> crate::params::Schema;
}

/// A closed set of values given by a whole number (a size that picks a compiled type).
pub trait Counted: Copy + PartialEq + std::fmt::Debug + 'static {
    /// The numbers, in declaration order.
    const VALUES: &'static [usize];
    /// The values, in the same order.
    const ALL: &'static [Self];

    fn value(self) -> usize;

    /// The value numbered `n`, if any.
    fn from_value(n: usize) -> Option<Self> {
        Self::VALUES
            .iter()
            .position(|v| *v == n)
            .map(|i| Self::ALL[i])
    }
}

/// Declares an enum of named values (`Variant => "name"`) implementing [`Named`], of counted
/// values (`Variant = 8`) implementing [`Counted`], or the kinds of a family of models
/// (`enum K in "family" { Variant => "name": schema }`) implementing [`Named`] and [`Kinds`]:
///
/// ```
/// landing_core::named! {
///     /// Two ways to read the surface.
///     pub enum Variant { Printed => "printed", Exact => "exact" }
/// }
/// use landing_core::params::Named;
/// assert_eq!(Variant::NAMES, &["printed", "exact"]);
/// assert_eq!(Variant::Exact.name(), "exact");
/// assert_eq!(Variant::from_name("exact"), Some(Variant::Exact));
/// ```
#[macro_export]
macro_rules! named {
    ($(#[$meta:meta])* $vis:vis enum $name:ident {
        $($(#[$vmeta:meta])* $variant:ident => $text:literal),* $(,)?
    }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        $vis enum $name {
            $($(#[$vmeta])* $variant,)*
        }

        impl $name {
            /// The names, in declaration order.
            pub const NAMES: &'static [&'static str] = &[$($text),*];
            /// The values, in the same order.
            pub const ALL: &'static [Self] = &[$(Self::$variant),*];

            /// The value's name at the boundary.
            pub fn name(self) -> &'static str {
                match self {
                    $(Self::$variant => $text,)*
                }
            }
        }

        impl $crate::params::Named for $name {
            const NAMES: &'static [&'static str] = $name::NAMES;
            const ALL: &'static [Self] = $name::ALL;

            fn name(self) -> &'static str {
                $name::name(self)
            }
        }
    };
    ($(#[$meta:meta])* $vis:vis enum $name:ident in $family:literal {
        $($(#[$vmeta:meta])* $variant:ident => $text:literal: $schema:expr),* $(,)?
    }) => {
        $crate::named! {
            $(#[$meta])*
            $vis enum $name {
                $($(#[$vmeta])* $variant => $text,)*
            }
        }

        impl $crate::params::Kinds for $name {
            const FAMILY: &'static str = $family;

            fn schema(self) -> $crate::params::Schema {
                match self {
                    $(Self::$variant => $schema,)*
                }
            }
        }
    };
    ($(#[$meta:meta])* $vis:vis enum $name:ident {
        $($(#[$vmeta:meta])* $variant:ident = $value:literal),* $(,)?
    }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        $vis enum $name {
            $($(#[$vmeta])* $variant,)*
        }

        impl $name {
            /// The numbers, in declaration order.
            pub const VALUES: &'static [usize] = &[$($value),*];
            /// The values, in the same order.
            pub const ALL: &'static [Self] = &[$(Self::$variant),*];

            /// The value's number.
            pub fn value(self) -> usize {
                match self {
                    $(Self::$variant => $value,)*
                }
            }
        }

        impl $crate::params::Counted for $name {
            const VALUES: &'static [usize] = $name::VALUES;
            const ALL: &'static [Self] = $name::ALL;

            fn value(self) -> usize {
                $name::value(self)
            }
        }
    };
}
