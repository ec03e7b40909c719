//! `reconstruct`'s keyword arguments as a `condt::Params`, with the command line's names and
//! rules.
//!
//! Owns: the names (each `condt reconstruct` option, `-` written `_`), their types, and the
//! contradictions the command line refuses, and those of the keywords it has no option for
//! (`outlier_filter=True`, `manifold_fix=True`, which say what `--iqr` and `--repair` imply). It
//! may not check a value's range: `Params::check` does, as for the command line, and its refusal
//! is reported with the keyword.
//!
//! | keyword | command line | `Params` |
//! |---|---|---|
//! | `paper=True` | `--paper` | `Params::paper()` as the start instead of `Params::default()` |
//! | `u=X` | `--u X` | `uniformity = Fixed(X)` |
//! | `adaptive=True` | `--adaptive` | `uniformity = Adaptive` |
//! | `iqr=K` / `iqr=None` | `--iqr K` / `--no-outlier-filter` | `outlier_factor` |
//! | `outlier_filter=False` / `True` | `--no-outlier-filter` / none | `outlier_factor = None` / kept |
//! | `outliers_first=B` | `--outliers-first` | `outliers_first` |
//! | `iqr_floor=B` | `--[no-]iqr-floor` | `iqr_floor` |
//! | `repair_again=B`, `local_outliers=B`, `clumps=B`, `confirm_given_back=B`, `close_gaps=B`, `junctions=B`, `crossings=B`, `tips=B`, `spikes=B`, `hooks=B`, `tails=B`, `detours=B` | `--[no-]FLAG` (`Stage::switch`) | `set_stage` |
//! | `smooth=B` | `--[no-]smooth` | `smooth` |
//! | `repair=MODE` | `--repair MODE` | `repair` |
//! | `manifold_fix=False` / `True` | `--no-manifold-fix` / none | `repair = Off` / kept |
//! | `method=M` | `--method M` | `method` |
//! | `sequential=B` | `--sequential` | `parallel = !B` |

use condt::{Method, Params, Repair, Stage, Uniformity};
use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};

/// The keywords other than `paper` and the stage switches, for the message on an unknown one.
const KEYWORDS: &[&str] = &[
    "u",
    "adaptive",
    "iqr",
    "outlier_filter",
    "outliers_first",
    "iqr_floor",
    "smooth",
    "repair",
    "manifold_fix",
    "method",
    "sequential",
];

/// The repair modes, by the command line's names.
const REPAIR_MODES: &[(&str, Repair)] = &[
    ("needs", Repair::Needs),
    ("paper", Repair::Paper),
    ("mutual", Repair::Mutual),
    ("crossing", Repair::CrossingAware),
    ("off", Repair::Off),
];

/// The methods, by the command line's names.
const METHODS: &[(&str, Method)] = &[
    ("condt", Method::ConDT),
    ("nn-crust", Method::NnCrust),
    ("crust", Method::Crust),
];

/// A stage's switch as a keyword: its command-line flag with `_` for `-`.
pub(crate) fn switch_keyword(stage: Stage) -> Option<String> {
    stage.switch().map(|switch| switch.flag.replace('-', "_"))
}

/// One setting that two keywords can make (`u` and `adaptive`; whether the outlier filter runs,
/// `iqr` and `outlier_filter`; whether the repair runs, `repair` and `manifold_fix`): a second
/// keyword saying otherwise is refused, as the command line refuses `--u 2 --adaptive`.
struct Setting<T> {
    value: Option<(T, String)>,
}

impl<T: PartialEq> Setting<T> {
    fn new() -> Self {
        Setting { value: None }
    }

    fn set(&mut self, value: T, said: String) -> PyResult<()> {
        match &self.value {
            Some((old, old_said)) if *old != value => Err(PyValueError::new_err(format!(
                "{old_said} and {said} contradict each other: give one of them"
            ))),
            Some(_) => Ok(()),
            None => {
                self.value = Some((value, said));
                Ok(())
            }
        }
    }

    fn get(self) -> Option<T> {
        self.value.map(|(value, _)| value)
    }
}

pub(crate) fn type_name(value: &Bound<'_, PyAny>) -> String {
    value
        .get_type()
        .name()
        .map_or_else(|_| "?".into(), |name| name.to_string())
}

/// Whether `value` is a bool: Python's, or numpy's (`numpy.bool`, `numpy.bool_` before numpy 2).
pub(crate) fn is_bool(value: &Bound<'_, PyAny>) -> bool {
    if value.is_instance_of::<PyBool>() {
        return true;
    }
    let kind = value.get_type();
    let module = kind.module().map(|m| m.to_string()).unwrap_or_default();
    module == "numpy" && matches!(type_name(value).as_str(), "bool" | "bool_")
}

/// A `bool` keyword's value: `True` or `False` (or numpy's bool), nothing else.
fn boolean(name: &str, value: &Bound<'_, PyAny>) -> PyResult<bool> {
    if is_bool(value) {
        if let Ok(on) = value.is_truthy() {
            return Ok(on);
        }
    }
    Err(PyTypeError::new_err(format!(
        "{name} must be True or False, not {}",
        type_name(value)
    )))
}

/// A number keyword's value: anything Python converts with `float()` by its `__float__` (an
/// int, a float, numpy's numbers), but not a bool nor a str; whether the library accepts it is
/// `Params::check`'s to say. A number too large for a float (`2**2000`, whose `float()` raises
/// `OverflowError`) is infinite, with its sign: a number all the same, which the check refuses
/// as it refuses `float("inf")`, naming the keyword.
pub(crate) fn number(name: &str, value: &Bound<'_, PyAny>) -> PyResult<f64> {
    if !is_bool(value) {
        match value.extract::<f64>() {
            Ok(x) => return Ok(x),
            Err(err) if err.is_instance_of::<PyOverflowError>(value.py()) => {
                return Ok(if value.lt(0)? {
                    f64::NEG_INFINITY
                } else {
                    f64::INFINITY
                });
            }
            Err(_) => {}
        }
    }
    Err(PyTypeError::new_err(format!(
        "{name} must be a number, not {}",
        type_name(value)
    )))
}

/// A name among `choices` (`repair`, `method`).
fn choice<T: Copy>(name: &str, value: &Bound<'_, PyAny>, choices: &[(&str, T)]) -> PyResult<T> {
    let names = choices
        .iter()
        .map(|(n, _)| format!("'{n}'"))
        .collect::<Vec<_>>()
        .join(", ");
    let text: String = value.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "{name} must be a str, one of {names}; not {}",
            type_name(value)
        ))
    })?;
    choices
        .iter()
        .find(|(n, _)| *n == text)
        .map(|&(_, v)| v)
        .ok_or_else(|| {
            let repr = value
                .repr()
                .map_or_else(|_| text.clone(), |r| r.to_string());
            PyValueError::new_err(format!("{name}={repr}: must be one of {names}"))
        })
}

/// The parameters the keywords `kwargs` (`paper` among them) ask for, checked as the command
/// line checks them.
///
/// # Errors
/// `TypeError` for an unknown keyword or a value of the wrong type; `ValueError` for two
/// keywords that contradict each other, a ConDT keyword beside a baseline method, or a value the
/// library refuses (`Params::check`).
pub(crate) fn params(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Params> {
    // `paper=True` chooses the starting point wherever it stands; the other keywords adjust it.
    let paper_given = kwargs.map(|d| d.get_item("paper")).transpose()?.flatten();
    let paper = match &paper_given {
        Some(value) => boolean("paper", value)?,
        None => false,
    };
    let mut params = if paper {
        Params::paper()
    } else {
        Params::default()
    };
    let mut uniformity = Setting::new();
    // Whether the outlier filter runs (`iqr=None` and `outlier_filter=False` say no; `iqr=K`
    // and `outlier_filter=True` say yes), and its factor when `iqr` gives one.
    let mut filter = Setting::new();
    let mut factor = None;
    // Whether the repair runs (`repair="off"` and `manifold_fix=False` say no, any other mode and
    // `manifold_fix=True` yes), and its mode when `repair` gives one.
    let mut repairing = Setting::new();
    let mut repair_mode = None;
    let mut method = None;
    // ConDT's own keywords as given, to refuse them beside a baseline method.
    let mut condt_keywords: Vec<String> = Vec::new();
    // Whatever its value, as every ConDT keyword (`paper=False` passed beside a baseline while
    // `smooth=True` was refused: a researcher's review).
    if paper_given.is_some() {
        condt_keywords.push(if paper { "paper=True" } else { "paper=False" }.into());
    }
    // As given, when they turn something on: a step the other keywords leave no way to run is
    // refused, as the command line refuses it (`refuse_steps_that_cannot_run` there).
    let mut named_on: Vec<(Stage, String)> = Vec::new();
    let (mut iqr_floor_said, mut outliers_first_said) = (None::<String>, None::<String>);
    let switches: Vec<(Stage, String)> = Stage::ALL
        .into_iter()
        .filter_map(|stage| switch_keyword(stage).map(|k| (stage, k)))
        .collect();
    for (key, value) in kwargs.into_iter().flat_map(|d| d.iter()) {
        let name: String = key.extract()?;
        let name = name.as_str();
        let repr = value.repr().map_or_else(|_| "?".into(), |r| r.to_string());
        let said = format!("{name}={repr}");
        if name != "method" && name != "sequential" && name != "paper" {
            condt_keywords.push(said.clone());
        }
        match name {
            // Read above.
            "paper" => {}
            "u" => uniformity.set(Uniformity::Fixed(number(name, &value)?), said)?,
            "adaptive" => {
                if boolean(name, &value)? {
                    uniformity.set(Uniformity::Adaptive, said)?;
                }
            }
            "iqr" => {
                if value.is_none() {
                    filter.set(false, said)?;
                } else {
                    factor = Some(number(name, &value)?);
                    filter.set(true, said)?;
                }
            }
            "outlier_filter" => filter.set(boolean(name, &value)?, said)?,
            "outliers_first" => {
                params.outliers_first = boolean(name, &value)?;
                if params.outliers_first {
                    outliers_first_said = Some(said);
                }
            }
            "iqr_floor" => {
                params.iqr_floor = boolean(name, &value)?;
                if params.iqr_floor {
                    iqr_floor_said = Some(said);
                }
            }
            "smooth" => params.smooth = boolean(name, &value)?,
            "repair" => {
                let mode = choice(name, &value, REPAIR_MODES)?;
                repair_mode = Some(mode);
                repairing.set(mode != Repair::Off, said)?;
            }
            "manifold_fix" => repairing.set(boolean(name, &value)?, said)?,
            "method" => method = Some((choice(name, &value, METHODS)?, said)),
            "sequential" => params.parallel = !boolean(name, &value)?,
            _ => match switches.iter().find(|(_, keyword)| keyword == name) {
                Some(&(stage, _)) => {
                    let on = boolean(name, &value)?;
                    params.set_stage(stage, on);
                    if on {
                        named_on.push((stage, said));
                    }
                }
                None => {
                    let known: Vec<&str> = KEYWORDS
                        .iter()
                        .copied()
                        .chain(switches.iter().map(|(_, k)| k.as_str()))
                        .collect();
                    return Err(PyTypeError::new_err(format!(
                        "reconstruct() got an unexpected keyword argument '{name}'; the \
                         parameters are paper, {}",
                        known.join(", ")
                    )));
                }
            },
        }
    }
    if let Some(u) = uniformity.get() {
        params.uniformity = u;
    }
    match filter.get() {
        Some(false) => params.outlier_factor = None,
        // Both starting points filter (k = 1.7); `outlier_filter=True` alone keeps theirs.
        Some(true) => params.outlier_factor = factor.or(params.outlier_factor),
        None => {}
    }
    match repairing.get() {
        Some(false) => params.repair = Repair::Off,
        // `manifold_fix=True` alone keeps the starting point's mode (both repair).
        Some(true) => params.repair = repair_mode.unwrap_or(params.repair),
        None => {}
    }
    if let Some((chosen, said)) = method {
        if chosen != Method::ConDT {
            if let Some(keyword) = condt_keywords.first() {
                return Err(PyValueError::new_err(format!(
                    "{keyword} sets a ConDT stage or parameter, but {said} chooses a baseline, \
                     which has none"
                )));
            }
        }
        params.method = chosen;
    }
    if params.method == Method::ConDT {
        let running = params.stages();
        if let Some((stage, said)) = named_on.iter().find(|(stage, _)| !running.contains(stage)) {
            let needs = match stage {
                Stage::RepairAgain => "the repair and then the outlier filter",
                Stage::GivenBack => "the local outlier removal",
                _ => "other steps",
            };
            return Err(PyValueError::new_err(format!(
                "{said} needs {needs}, which the other parameters turn off"
            )));
        }
        if let (Some(said), None) = (&iqr_floor_said, params.outlier_factor) {
            return Err(PyValueError::new_err(format!(
                "{said} sets the outlier filter's spacing floor, but the filter is off"
            )));
        }
        let both = params.outlier_factor.is_some() && params.repair != Repair::Off;
        if let (Some(said), false) = (&outliers_first_said, both) {
            return Err(PyValueError::new_err(format!(
                "{said} runs the outlier filter before the repair, but one of them is off"
            )));
        }
    }
    params
        .check()
        .map_err(|err| crate::convert::library_error(err, &[]))?;
    Ok(params)
}
