//! Fuzzy variable-rate reaching law (seed 002 sec. 2.3).
//!
//! The integral surface of law 4, with the switching term eps sgn(s) replaced by the output of
//! a Mamdani system whose inputs are s and s' (5 sets each on [-5, 5]) and whose output lies on
//! [-4, 4] (7 sets), the seed's Table 1 rules:
//!
//! ```text
//! u = q_ref'' - drift - c1 sigma - c2 sigma' + k s + ku * F(ke s, kec s')
//! ```
//!
//! The rule table is signed (s NB and s' NB give NB, s PB and s' PB give PB), so its output
//! plays eps sgn(s) itself: it pushes harder the faster s moves away from the surface. ke, kec
//! and ku are the input and output scaling factors. s' is not measured: the law takes the
//! backward difference of s over the control period (0 at the first instant), as a sampled
//! implementation would.

use std::sync::Arc;

use nalgebra::SVector;

use super::integral_reaching::{C1, C2, IntegralSurface, K};
use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check_axes};
use crate::fuzzy::Mamdani;
use crate::lanes::{Real, add, sub, zeros};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

const KE: Param = Param::axes("ke")
    .unit("s/q")
    .rule("ke > 0")
    .doc("input scaling of s onto the system's universe");
const KEC: Param = Param::axes("kec")
    .unit("s^2/q")
    .rule("kec > 0")
    .doc("input scaling of s' onto the system's universe");
const KU: Param = Param::axes("ku")
    .unit("q/s^2")
    .rule("ku > 0")
    .doc("output scaling: command units per unit of the output universe");
const SYSTEM: Param = Param::fuzzy_system("system")
    .rule("two inputs (s and s')")
    .doc("the Mamdani system F(ke s, kec s')");

#[derive(Clone, Debug, PartialEq)]
pub struct FuzzyVariableRate<const D: usize, R = f64> {
    pub surface: IntegralSurface<D, R>,
    /// Input scaling of s onto the universe.
    pub ke: SVector<R, D>,
    /// Input scaling of s'.
    pub kec: SVector<R, D>,
    /// Output scaling of the fuzzy output, m/s^2 per unit.
    pub ku: SVector<R, D>,
    /// Shared by a block.
    pub system: Arc<Mamdani>,
}

crate::gather_struct!(FuzzyVariableRate<const D: usize, R> {
    lanes: [surface, ke, kec, ku],
    shared: [system],
});

/// Integral of the surface, the previous s and whether there is one (every case of a block
/// starts at the same instant, so the flag is shared).
#[derive(Clone, Copy, Debug)]
pub struct VariableRateMemory<const D: usize, R> {
    integral: SVector<R, D>,
    previous_s: SVector<R, D>,
    started: bool,
}

impl<const D: usize, R: Real> FuzzyVariableRate<D, R> {
    /// (s, s', fuzzy output scaled by ku) at this instant.
    #[inline(always)]
    fn terms(
        &self,
        m: &VariableRateMemory<D, R>,
        input: &LawInput<D, R>,
    ) -> (SVector<R, D>, SVector<R, D>, SVector<R, D>) {
        let s = self.surface.s(&m.integral, input);
        let ds = if m.started {
            let mut ds = sub(&s, &m.previous_s);
            for i in 0..D {
                ds[i] = ds[i] / input.dt;
            }
            ds
        } else {
            zeros()
        };
        // the axes' systems evaluated side by side (`Mamdani::evaluate_each`)
        // (the system's two inputs: `validate` checks it has two)
        let mut x = [[R::zero(); 2]; D];
        for (i, x) in x.iter_mut().enumerate() {
            x[0] = self.ke[i] * s[i];
            x[1] = self.kec[i] * ds[i];
        }
        let eps = self.system.evaluate_each(&x);
        let mut out = s;
        for i in 0..D {
            out[i] = self.ku[i] * eps[i];
        }
        (s, ds, out)
    }
}

impl<const D: usize, R: Real> ControlLaw<R, D> for FuzzyVariableRate<D, R> {
    type Memory = VariableRateMemory<D, R>;
    const DIAGNOSTICS: &'static [&'static str] = &["s", "s_dot", "epsilon"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) -> VariableRateMemory<D, R> {
        VariableRateMemory {
            integral: zeros(),
            previous_s: zeros(),
            started: false,
        }
    }

    #[inline(always)]
    fn command(&self, m: &VariableRateMemory<D, R>, input: &LawInput<D, R>) -> SVector<R, D> {
        let (s, _, fuzzy) = self.terms(m, input);
        add(&self.surface.smooth_part(&s, input), &fuzzy)
    }

    #[inline(always)]
    fn advance(&self, m: &mut VariableRateMemory<D, R>, input: &LawInput<D, R>) {
        m.previous_s = self.surface.s(&m.integral, input);
        m.started = true;
        self.surface.advance(&mut m.integral, input);
    }

    #[inline(always)]
    fn diagnostics(&self, m: &VariableRateMemory<D, R>, input: &LawInput<D, R>, out: &mut [R]) {
        let (s, ds, fuzzy) = self.terms(m, input);
        out[..D].copy_from_slice(s.as_slice());
        out[D..2 * D].copy_from_slice(ds.as_slice());
        out[2 * D..3 * D].copy_from_slice(fuzzy.as_slice());
    }
}

impl<const D: usize> Validate for FuzzyVariableRate<D> {
    fn validate(&self) -> Result<(), ParamError> {
        self.surface.validate()?;
        check_axes(&KE, self.ke.as_slice(), |v| v > 0.0)?;
        check_axes(&KEC, self.kec.as_slice(), |v| v > 0.0)?;
        check_axes(&KU, self.ku.as_slice(), |v| v > 0.0)?;
        if self.system.n_inputs() != 2 {
            return Err(ParamError::new(
                SYSTEM.name,
                self.system.n_inputs() as f64,
                SYSTEM.rule,
            ));
        }
        Ok(())
    }
}

impl<const D: usize> Declared for FuzzyVariableRate<D> {
    const SCHEMA: Schema = Schema::new(&[C1, C2, K, KE, KEC, KU, SYSTEM]);
}

impl<const D: usize> FromParams for FuzzyVariableRate<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            surface: IntegralSurface::from_params(p)?,
            ke: p.axes(&KE)?,
            kec: p.axes(&KEC)?,
            ku: p.axes(&KU)?,
            system: p.fuzzy_system(&SYSTEM)?,
        })
    }
}
