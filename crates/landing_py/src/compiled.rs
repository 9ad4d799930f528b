//! A table compiled for each axis count the plants use (3 for the landers, 2 for the tethered
//! satellite): a law, a reference or a disturbance does not know its plant until it meets it.

use std::any::Any;

use landing_core::PerCase;

use crate::errors::InputError;
use crate::table::{Cases, Table};

/// An error kept for later (the reading for the other axis count may be the one used).
#[derive(Clone, Debug)]
struct Kept {
    type_error: bool,
    message: String,
}

impl Kept {
    fn new(e: InputError) -> Self {
        match e {
            InputError::Type(m) => Self {
                type_error: true,
                message: m,
            },
            InputError::Value(m) => Self {
                type_error: false,
                message: m,
            },
            InputError::Py(p) => Self {
                type_error: false,
                message: p.to_string(),
            },
        }
    }

    fn error(&self) -> InputError {
        if self.type_error {
            InputError::Type(self.message.clone())
        } else {
            InputError::Value(self.message.clone())
        }
    }
}

type Entry = Result<Box<dyn Any + Send + Sync>, Kept>;

/// The readings of one table for D = 3 and D = 2.
pub struct ByAxes {
    three: Entry,
    two: Entry,
}

/// How a model is read for D axes, for D = 3 and D = 2.
pub trait ReadFor {
    type At<const D: usize>: Send + Sync + 'static;
    fn read<const D: usize>(p: &mut crate::table::Reader<'_>) -> Result<Self::At<D>, InputError>;
}

impl ByAxes {
    /// Reads `table` for 3 and 2 axes; fails only if neither reads, with the error of the
    /// reading `prefer_two` says the table was meant for.
    pub fn compile<M: ReadFor>(
        owner: &str,
        table: &Table,
        prefer_two: bool,
    ) -> Result<Self, InputError> {
        fn entry<T: Send + Sync + 'static>(
            owner: &str,
            r: Result<(PerCase<T>, Cases), InputError>,
        ) -> Entry {
            r.map(|v| Box::new(v) as Box<dyn Any + Send + Sync>)
                .map_err(|e| Kept::new(e.context(owner)))
        }
        let three = entry(owner, table.read_cases(None, |p| M::read::<3>(p)));
        let two = entry(owner, table.read_cases(None, |p| M::read::<2>(p)));
        if let (Err(e3), Err(e2)) = (&three, &two) {
            return Err(if prefer_two { e2.error() } else { e3.error() });
        }
        Ok(Self { three, two })
    }

    /// The reading for D axes (with its cases), or why the table does not fit D axes.
    pub fn get<T: Send + Sync + 'static, const D: usize>(
        &self,
    ) -> Result<(&PerCase<T>, &Cases), InputError> {
        let entry = match D {
            3 => &self.three,
            2 => &self.two,
            _ => return Err(InputError::value(format!("{D} axes are not supported"))),
        };
        match entry {
            Ok(b) => b
                .downcast_ref::<(PerCase<T>, Cases)>()
                .map(|(v, c)| (v, c))
                .ok_or_else(|| InputError::value("internal: a reading of another type")),
            Err(k) => Err(k.error()),
        }
    }

    /// The axis counts the table fits.
    pub fn axes(&self) -> Vec<usize> {
        let mut a = Vec::new();
        if self.two.is_ok() {
            a.push(2);
        }
        if self.three.is_ok() {
            a.push(3);
        }
        a
    }
}
