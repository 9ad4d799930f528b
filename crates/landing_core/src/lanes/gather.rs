//! Building the lanes of a block from the cases it holds.
//!
//! A batch keeps its plants, laws, references and disturbances as one-case values (`f64`
//! parameters, shared or one per case); a block of W cases runs on the same types with
//! [`Lanes<W>`](super::Lanes) parameters, lane i holding case i's value. [`Gather`] builds
//! the latter from the former, field by field; the [`gather_struct!`](crate::gather_struct)
//! macro writes it for a struct from the list of its fields.
//!
//! Some fields cannot differ between the lanes of a block: they choose code, not numbers (a
//! law's variant, a switching function's kind, a network's node count, a fuzzy system). They
//! are *shared* fields, taken from the block's first case; [`Gather::same_shape`] tells
//! whether two cases agree on all of them, which a batch checks once for all its cases.

use nalgebra::SVector;

use super::Real;

/// A value of a block built lane by lane from the one-case values of its cases.
pub trait Gather<R: Real>: Sized {
    /// The one-case value (`f64` parameters).
    type Case: 'static;

    /// The lanes of the cases `case(0) .. case(R::LANES - 1)`.
    fn gather<'a>(case: &dyn Fn(usize) -> &'a Self::Case) -> Self;

    /// Whether two cases agree on the fields that must be shared by a block.
    fn same_shape(_a: &Self::Case, _b: &Self::Case) -> bool {
        true
    }
}

impl<R: Real> Gather<R> for R {
    type Case = f64;
    #[inline]
    fn gather<'a>(case: &dyn Fn(usize) -> &'a f64) -> Self {
        R::from_fn(|i| *case(i))
    }
}

impl<R: Real, const N: usize> Gather<R> for SVector<R, N> {
    type Case = SVector<f64, N>;
    #[inline]
    fn gather<'a>(case: &dyn Fn(usize) -> &'a SVector<f64, N>) -> Self {
        SVector::from_fn(|j, _| R::from_fn(|i| case(i)[j]))
    }
}

impl<R: Real, T: Gather<R>, const K: usize> Gather<R> for [T; K] {
    type Case = [T::Case; K];
    #[inline]
    fn gather<'a>(case: &dyn Fn(usize) -> &'a [T::Case; K]) -> Self {
        std::array::from_fn(|k| T::gather(&|i| &case(i)[k]))
    }
    fn same_shape(a: &Self::Case, b: &Self::Case) -> bool {
        a.iter().zip(b).all(|(x, y)| T::same_shape(x, y))
    }
}

/// An optional part (a sensor): whether it is there is the block's, its numbers each lane's.
impl<R: Real, T: Gather<R>> Gather<R> for Option<T> {
    type Case = Option<T::Case>;
    #[inline]
    fn gather<'a>(case: &dyn Fn(usize) -> &'a Option<T::Case>) -> Self {
        case(0).as_ref().map(|_| {
            T::gather(&|i| {
                case(i)
                    .as_ref()
                    .expect("a block's cases all have the part or none has (same_shape)")
            })
        })
    }
    fn same_shape(a: &Self::Case, b: &Self::Case) -> bool {
        match (a, b) {
            (Some(x), Some(y)) => T::same_shape(x, y),
            (None, None) => true,
            _ => false,
        }
    }
}

/// [`Gather::same_shape`] of a field, its type named by a projection from the lane struct.
#[doc(hidden)]
#[inline]
pub fn same_field<R: Real, S, T: Gather<R>>(
    _field: impl Fn(&S) -> &T,
    a: &T::Case,
    b: &T::Case,
) -> bool {
    T::same_shape(a, b)
}

/// Implements [`Gather`] for a struct generic over its number type `R` (and const
/// parameters), from the list of its lane fields (numbers, vectors, nested gatherable
/// structs) and of its shared fields (compared with `==`):
///
/// ```ignore
/// gather_struct!(FixedTimeMss<const D: usize, R> {
///     lanes: [beta1, beta2, q1, q2, alpha1, alpha2, gamma1, gamma2, s1_floor],
///     shared: [variant],
/// });
/// ```
#[macro_export]
macro_rules! gather_struct {
    ($name:ident<$(const $c:ident: usize,)* R> {
        lanes: [$($l:ident),* $(,)?],
        shared: [$($s:ident),* $(,)?] $(,)?
    }) => {
        impl<$(const $c: usize,)* R: $crate::lanes::Real> $crate::lanes::Gather<R>
            for $name<$($c,)* R>
        {
            type Case = $name<$($c,)* f64>;

            fn gather<'a>(case: &dyn Fn(usize) -> &'a Self::Case) -> Self {
                Self {
                    $($l: $crate::lanes::Gather::<R>::gather(&|i| &case(i).$l),)*
                    $($s: case(0).$s.clone(),)*
                }
            }

            #[allow(unused_variables)]
            fn same_shape(a: &Self::Case, b: &Self::Case) -> bool {
                true $(&& $crate::lanes::gather::same_field::<R, Self, _>(|s| &s.$l, &a.$l, &b.$l))*
                    $(&& a.$s == b.$s)*
            }
        }
    };
}
