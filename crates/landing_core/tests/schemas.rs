//! Every registered kind reads exactly the parameters it declares.
//!
//! A recording [`ParamSource`] answers every read with a plausible value and notes which
//! declared parameter it was asked for, with which method. Each choice it is asked to make (a
//! table's kind, a law's variant, a switching function, the tether's fidelity, a node count)
//! is explored: the reading is run again for every combination. Then, in every branch, each
//! table must have been asked for nothing it does not declare, with the method its shape
//! implies (an optional parameter through `opt_*`), and for every parameter it declares (read
//! or skipped: the Python layer always gives every key); and across the branches each
//! declared parameter must be read (not only skipped) at least once. Every kind of every
//! family must be reached.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use nalgebra::SVector;

use landing_core::control::AnyLaw;
use landing_core::dispersion::Dispersion;
use landing_core::disturbance::{COMPONENTS, Disturbance};
use landing_core::error::ReadError;
use landing_core::fuzzy::{Mamdani, TRAPEZOID, TRIANGLE, variable_rate_system};
use landing_core::params::{
    Counted, Declared, FromParams, Kinds, Layout, Named, Param, ParamSource, Shape,
};
use landing_core::reference::Reference;
use landing_core::registry::{AnyGravity, PlantCase, schemas};

/// The choices of one run: the option taken at each choice point, in order, and how many
/// options each had.
#[derive(Default)]
struct Path {
    taken: Vec<usize>,
    widths: Vec<usize>,
}

impl Path {
    /// The option at the next choice point among `n`.
    fn choose(&mut self, n: usize) -> usize {
        let k = self.widths.len();
        if k == self.taken.len() {
            self.taken.push(0);
        }
        self.widths.push(n);
        self.taken[k]
    }

    /// The next combination after this run's (depth first), if any.
    fn next(mut self) -> Option<Path> {
        self.taken.truncate(self.widths.len());
        while let Some(last) = self.taken.pop() {
            let width = self.widths[self.taken.len()];
            if last + 1 < width {
                self.taken.push(last + 1);
                return Some(Path {
                    taken: self.taken,
                    widths: Vec::new(),
                });
            }
        }
        None
    }
}

/// One table of a run: what it declares (once its kind is known) and what was asked of it.
#[derive(Default)]
struct Scope {
    declared: Option<&'static [Param]>,
    family: Option<&'static str>,
    read: BTreeSet<&'static str>,
    skipped: BTreeSet<&'static str>,
}

struct Recorder {
    path: Path,
    /// The table being read, by its path (`law:ntsmc`, `plant:small_body/gravity`...).
    at: String,
    scopes: BTreeMap<String, Scope>,
    problems: Vec<String>,
    /// The kinds reached, as `family:kind`.
    reached: BTreeSet<String>,
}

impl Recorder {
    fn new(
        path: Path,
        root: &str,
        declared: Option<&'static [Param]>,
        family: &'static str,
    ) -> Self {
        let mut scopes = BTreeMap::new();
        scopes.insert(
            root.to_string(),
            Scope {
                declared,
                family: Some(family),
                ..Scope::default()
            },
        );
        Self {
            path,
            at: root.to_string(),
            scopes,
            problems: Vec::new(),
            reached: BTreeSet::new(),
        }
    }

    fn scope(&mut self) -> &mut Scope {
        self.scopes.entry(self.at.clone()).or_default()
    }

    /// Notes a read of `p` by `method`, which must suit its declaration.
    fn note(&mut self, p: &Param, method: &str, ok: impl Fn(&Param) -> bool) {
        let at = self.at.clone();
        let scope = self.scope();
        match scope.declared.and_then(|d| d.iter().find(|q| q.name == p.name)) {
            None => self
                .problems
                .push(format!("{at}: reads {} ({method}), which it does not declare", p.name)),
            Some(declared) if declared != p => self
                .problems
                .push(format!("{at}: reads {} through another declaration", p.name)),
            Some(declared) if !ok(declared) => self.problems.push(format!(
                "{at}: reads {} with {method}, which its declaration ({:?}, required {}) does not suit",
                p.name, declared.shape, declared.required
            )),
            Some(_) => {
                self.scope().read.insert(p.name);
            }
        }
    }

    fn within<T>(
        &mut self,
        sub: String,
        layout: Layout,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError> {
        let outer = std::mem::replace(&mut self.at, sub);
        let scope = self.scope();
        match layout {
            Layout::Family(f) => scope.family = Some(f),
            Layout::Fixed(params) => scope.declared = Some(params),
        }
        let r = read(self);
        self.at = outer;
        r
    }
}

fn layout_of(p: &Param) -> Option<Layout> {
    match p.shape {
        Shape::Nested(l) | Shape::List(l) => Some(l),
        _ => None,
    }
}

impl ParamSource for Recorder {
    fn scalar(&mut self, p: &Param) -> Result<f64, ReadError> {
        self.note(p, "scalar", |d| d.shape == Shape::Scalar && d.required);
        Ok(1.0)
    }

    fn opt_scalar(&mut self, p: &Param) -> Result<Option<f64>, ReadError> {
        self.note(p, "opt_scalar", |d| d.shape == Shape::Scalar && !d.required);
        Ok(Some(1.0))
    }

    fn axes<const D: usize>(&mut self, p: &Param) -> Result<SVector<f64, D>, ReadError> {
        self.note(p, "axes", |d| d.shape == Shape::PerAxis && d.required);
        Ok(SVector::repeat(1.0))
    }

    fn opt_axes<const D: usize>(
        &mut self,
        p: &Param,
    ) -> Result<Option<SVector<f64, D>>, ReadError> {
        self.note(p, "opt_axes", |d| d.shape == Shape::PerAxis && !d.required);
        Ok(Some(SVector::repeat(1.0)))
    }

    fn components(&mut self, p: &Param) -> Result<Vec<f64>, ReadError> {
        self.note(p, "components", |d| d.shape == Shape::PerComponent);
        // a fuzzy set's corners, so that its reading goes on
        Ok(if *p == TRAPEZOID {
            vec![0.0, 1.0, 2.0, 3.0]
        } else {
            vec![0.0, 1.0, 2.0]
        })
    }

    fn case_components(&mut self, p: &Param) -> Result<Vec<f64>, ReadError> {
        self.note(p, "case_components", |d| {
            d.shape == Shape::PerComponent && d.case_rows
        });
        Ok(vec![1.0])
    }

    fn choice<T: Named>(&mut self, p: &Param) -> Result<T, ReadError> {
        self.note(p, "choice", |d| d.shape == Shape::Choice(T::NAMES));
        Ok(T::ALL[self.path.choose(T::ALL.len())])
    }

    fn flag(&mut self, p: &Param) -> Result<bool, ReadError> {
        self.note(p, "flag", |d| d.shape == Shape::Flag);
        Ok(true)
    }

    fn count(&mut self, p: &Param) -> Result<usize, ReadError> {
        self.note(p, "count", |d| matches!(d.shape, Shape::Count(_)));
        match p.shape {
            Shape::Count(allowed) => Ok(allowed[self.path.choose(allowed.len())]),
            _ => Ok(1),
        }
    }

    fn count_of<T: Counted>(&mut self, p: &Param) -> Result<T, ReadError> {
        self.note(p, "count_of", |d| d.shape == Shape::Count(T::VALUES));
        Ok(T::ALL[self.path.choose(T::ALL.len())])
    }

    fn kind<T: Kinds>(&mut self) -> Result<T, ReadError> {
        let kind = T::ALL[self.path.choose(T::ALL.len())];
        let at = self.at.clone();
        let scope = self.scope();
        if scope.family != Some(T::FAMILY) {
            let expected = scope.family;
            self.problems.push(format!(
                "{at}: reads a {} kind where {expected:?} was declared",
                T::FAMILY
            ));
        }
        let scope = self.scope();
        match scope.declared {
            // a table read again (the small body's gravity) keeps its kind
            Some(d) if d == kind.schema().params => {}
            Some(_) => self
                .problems
                .push(format!("{at}: its kind read twice, differently")),
            None => scope.declared = Some(kind.schema().params),
        }
        self.reached
            .insert(format!("{}:{}", T::FAMILY, kind.name()));
        Ok(kind)
    }

    fn nested<T>(
        &mut self,
        p: &Param,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError> {
        self.note(p, "nested", |d| matches!(d.shape, Shape::Nested(_)));
        let sub = format!("{}/{}", self.at, p.name);
        self.within(sub, layout_of(p).expect("a nested table's layout"), read)
    }

    fn opt_nested<T>(
        &mut self,
        p: &Param,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<Option<T>, ReadError> {
        self.note(p, "opt_nested", |d| {
            matches!(d.shape, Shape::Nested(_)) && !d.required
        });
        let sub = format!("{}/{}", self.at, p.name);
        self.within(sub, layout_of(p).expect("a nested table's layout"), read)
            .map(Some)
    }

    fn list_len(&mut self, p: &Param) -> Result<usize, ReadError> {
        self.note(p, "list_len", |d| matches!(d.shape, Shape::List(_)));
        Ok(1)
    }

    fn list_item<T>(
        &mut self,
        p: &Param,
        index: usize,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError> {
        self.note(p, "list_item", |d| matches!(d.shape, Shape::List(_)));
        let sub = format!("{}/{}[{index}]", self.at, p.name);
        self.within(sub, layout_of(p).expect("a list's layout"), read)
    }

    fn fuzzy_system(&mut self, p: &Param) -> Result<Arc<Mamdani>, ReadError> {
        self.note(p, "fuzzy_system", |d| d.shape == Shape::FuzzySystem);
        Ok(Arc::new(variable_rate_system(11)))
    }

    fn skip(&mut self, p: &Param) {
        let at = self.at.clone();
        let scope = self.scope();
        if scope.declared.is_some_and(|d| d.contains(p)) {
            scope.skipped.insert(p.name);
        } else {
            self.problems
                .push(format!("{at}: skips {}, which it does not declare", p.name));
        }
    }
}

/// What every branch of one reader asked for: the problems found, the parameters read
/// (not only skipped) in some branch, by table and kind, and the kinds reached.
#[derive(Default)]
struct Findings {
    problems: Vec<String>,
    read: BTreeMap<String, BTreeSet<&'static str>>,
    declared: BTreeMap<String, BTreeSet<&'static str>>,
    reached: BTreeSet<String>,
    branches: usize,
}

/// Runs `read` over every combination of its choices.
fn explore(
    findings: &mut Findings,
    root: &str,
    declared: Option<&'static [Param]>,
    family: &'static str,
    read: impl Fn(&mut Recorder),
) {
    let mut path = Some(Path::default());
    while let Some(p) = path {
        let mut r = Recorder::new(p, root, declared, family);
        read(&mut r);
        findings.branches += 1;
        findings.problems.extend(r.problems);
        for (at, scope) in &r.scopes {
            let Some(declared) = scope.declared else {
                findings.problems.push(format!("{at}: read without a kind"));
                continue;
            };
            // the table's identity across branches: its path, with its kind when it has one
            let id = format!(
                "{at} {:?}",
                declared.iter().map(|p| p.name).collect::<Vec<_>>()
            );
            let names: BTreeSet<_> = declared.iter().map(|p| p.name).collect();
            let touched: BTreeSet<_> = scope.read.union(&scope.skipped).copied().collect();
            for missing in names.difference(&touched) {
                findings.problems.push(format!(
                    "{at}: declares {missing}, which this branch neither reads nor skips"
                ));
            }
            findings
                .read
                .entry(id.clone())
                .or_default()
                .extend(&scope.read);
            findings.declared.insert(id, names);
        }
        findings.reached.extend(r.reached);
        path = r.path.next();
    }
}

#[test]
fn every_kind_reads_exactly_what_it_declares() {
    let mut f = Findings::default();
    explore(&mut f, "law", None, "law", |r| {
        let _ = AnyLaw::<3>::from_params(r);
    });
    explore(&mut f, "law (2 axes)", None, "law", |r| {
        let _ = AnyLaw::<2>::from_params(r);
    });
    explore(&mut f, "plant", None, "plant", |r| {
        let _ = PlantCase::from_params(r);
    });
    explore(&mut f, "gravity", None, "gravity", |r| {
        let _ = AnyGravity::from_params(r);
    });
    explore(&mut f, "reference", None, "reference", |r| {
        let _ = Reference::<3>::from_params(r);
    });
    explore(&mut f, "dispersion", None, "dispersion", |r| {
        let _ = Dispersion::from_params(r);
    });
    const DISTURBANCE: &[Param] = &[COMPONENTS];
    explore(
        &mut f,
        "disturbance",
        Some(DISTURBANCE),
        "disturbance",
        |r| {
            let _ = Disturbance::<3>::from_params(r);
        },
    );
    explore(
        &mut f,
        "fuzzy",
        Some(<Mamdani as Declared>::SCHEMA.params),
        "fuzzy",
        |r| {
            let _ = Mamdani::from_params(r);
        },
    );

    for (id, declared) in &f.declared {
        for never in declared.difference(&f.read[id]) {
            f.problems
                .push(format!("{id}: declares {never}, which no branch reads"));
        }
    }
    let mut kinds = BTreeSet::new();
    for (family, entries) in schemas() {
        for (kind, _) in entries {
            kinds.insert(format!("{family}:{kind}"));
        }
    }
    // the fuzzy system's own table has no kind: it is read as the root of its family
    kinds.remove("fuzzy:mamdani");
    for missing in kinds.difference(&f.reached) {
        f.problems.push(format!("{missing} is never reached"));
    }
    assert!(f.problems.is_empty(), "{}", f.problems.join("\n"));
    // the branches: 11 laws (with their variants and switches, 7 node counts of the RBF law)
    // on 2 axis counts, 3 small bodies, 5 tethers, ...
    assert!(f.branches > 60, "{} branches", f.branches);
}

#[test]
fn schemas_list_every_registered_kind_once() {
    let all = schemas();
    let families: Vec<_> = all.iter().map(|(f, _)| *f).collect();
    assert_eq!(
        families,
        [
            "plant",
            "law",
            "gravity",
            "disturbance",
            "reference",
            "dispersion",
            "sensor",
            "filter",
            "fuzzy"
        ]
    );
    for (family, kinds) in &all {
        let names: BTreeSet<_> = kinds.iter().map(|(k, _)| *k).collect();
        assert_eq!(names.len(), kinds.len(), "{family}: a kind listed twice");
        for (kind, schema) in kinds {
            let params: BTreeSet<_> = schema.params.iter().map(|p| p.name).collect();
            assert_eq!(
                params.len(),
                schema.params.len(),
                "{family}:{kind}: a parameter twice"
            );
            assert_eq!(
                schema.random.is_some(),
                *family == "disturbance",
                "{family}:{kind}"
            );
        }
    }
    assert_eq!(all[1].1.len(), landing_core::control::LAW_KINDS.len());
    assert_eq!(all[0].1.len(), landing_core::registry::PLANT_KINDS.len());
    let _ = TRIANGLE;
}
