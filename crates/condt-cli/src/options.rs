//! The options of the commands as tables: each entry names an option, its value and its help
//! line, and both the matching of the command line and the `Options:` section of the help are
//! made from the same entries, so the help cannot drift from what is accepted.
//!
//! Owns: how a command line is split into options, their values and operands ([`lexopt`]:
//! `--u 2.5` and `--u=2.5`, `-o FILE` and `-oFILE`, `--` ending the options, arguments that
//! need not be UTF-8) and how a table is written as help. What an option does is the command's
//! business (`cli.rs`, `score.rs`).

use crate::cli::{usage, CliError};
use lexopt::{Arg, Parser};
use std::ffi::OsString;

/// One option of a command.
#[derive(Clone)]
pub(crate) struct Opt<Id> {
    /// What the command does with it.
    pub(crate) id: Id,
    /// `-c`, if it has a short form.
    pub(crate) short: Option<char>,
    /// `--long`, without the dashes.
    pub(crate) long: &'static str,
    /// `--[no-]long`: `--no-long` is accepted too and turns the setting off.
    pub(crate) negatable: bool,
    /// The name of its value in the help (`FILE`); `None`: it takes none.
    pub(crate) value: Option<&'static str>,
    /// Its help, one or more lines; those after the first are indented under it.
    pub(crate) help: &'static str,
}

/// An option as given on the command line.
#[derive(Debug)]
pub(crate) struct Given<Id> {
    pub(crate) id: Id,
    /// `false` for `--no-long` of a negatable option.
    pub(crate) on: bool,
    /// As it was written, without its value: `-o`, `--output`, `--no-smooth`.
    pub(crate) flag: String,
    /// Its value; `None` for an option that takes one: the command line ended before it.
    pub(crate) value: Option<OsString>,
}

/// A command line split by a table.
#[derive(Debug)]
pub(crate) struct Lexed<Id> {
    /// The options in the order given.
    pub(crate) given: Vec<Given<Id>>,
    /// The other arguments (file names), in order; `-` among them.
    pub(crate) operands: Vec<OsString>,
}

fn find<'t, Id>(table: &'t [Opt<Id>], arg: &Arg<'_>) -> Option<(&'t Opt<Id>, bool)> {
    table.iter().find_map(|opt| match *arg {
        Arg::Short(c) => (opt.short == Some(c)).then_some((opt, true)),
        Arg::Long(name) if name == opt.long => Some((opt, true)),
        Arg::Long(name) if opt.negatable && name.strip_prefix("no-") == Some(opt.long) => {
            Some((opt, false))
        }
        _ => None,
    })
}

/// Values written as options (`--crust`, `--svg`: a newcomer's review, where `--crust` was
/// answered with `--crs`), by the option of `table` that takes them.
fn value_as_option<Id>(table: &[Opt<Id>], name: &str) -> Option<String> {
    const VALUES: [(&str, &[&str]); 2] = [
        ("method", &["condt", "crust", "nn-crust"]),
        ("format", &["edges", "npy", "txt", "svg", "geojson", "html"]),
    ];
    let (option, _) = VALUES
        .iter()
        .find(|(_, values)| values.contains(&name.to_ascii_lowercase().as_str()))?;
    let takes = table.iter().any(|opt| opt.long == *option);
    takes.then(|| format!("--{option} {}", name.to_ascii_lowercase()))
}

/// The long option of `table` (or its `no-` form) nearest `name` in edits, when one is within
/// a third of the name's length, rounded up: a typo's likely meaning (`--quite`).
fn nearest<Id>(table: &[Opt<Id>], name: &str) -> Option<String> {
    let names = table.iter().flat_map(|opt| {
        let negated = opt.negatable.then(|| format!("no-{}", opt.long));
        core::iter::once(opt.long.to_string()).chain(negated)
    });
    let limit = name.chars().count().div_ceil(3);
    names
        .map(|known| (edits(name, &known), known))
        .filter(|(distance, _)| *distance <= limit)
        .min_by_key(|(distance, _)| *distance)
        .map(|(_, known)| known)
}

/// Levenshtein distance between `a` and `b`, by characters (one row of the table at a time).
fn edits(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

fn written(arg: &Arg<'_>) -> String {
    match arg {
        Arg::Short(c) => format!("-{c}"),
        Arg::Long(name) => format!("--{name}"),
        Arg::Value(value) => value.to_string_lossy().into_owned(),
    }
}

/// Splits `args` by `table`. An option not in it is refused as `{context}unknown option -x`.
pub(crate) fn lex<Id: Copy>(
    args: &[OsString],
    table: &[Opt<Id>],
    context: &str,
) -> Result<Lexed<Id>, CliError> {
    let mut parser = Parser::from_args(args.iter().cloned());
    let mut lexed = Lexed {
        given: Vec::new(),
        operands: Vec::new(),
    };
    loop {
        let arg = match parser.next() {
            Ok(Some(arg)) => arg,
            Ok(None) => return Ok(lexed),
            Err(err) => return Err(refused(err)),
        };
        if let Arg::Value(operand) = arg {
            lexed.operands.push(operand);
            continue;
        }
        let flag = written(&arg);
        let Some((opt, on)) = find(table, &arg) else {
            let hint = match arg {
                Arg::Long(name) => value_as_option(table, name)
                    .or_else(|| nearest(table, name).map(|near| format!("--{near}")))
                    .map(|meant| format!(" (did you mean {meant}?)"))
                    .unwrap_or_default(),
                _ => String::new(),
            };
            return Err(usage(format!("{context}unknown option {flag}{hint}")));
        };
        // A value is taken as it is, even when it starts with `-` (`--u -1`, `-o -`).
        let value = match opt.value {
            Some(_) => parser.value().ok(),
            None => None,
        };
        lexed.given.push(Given {
            id: opt.id,
            on,
            flag,
            value,
        });
    }
}

/// What lexopt refuses on its own: a value given to an option that takes none (`--edges=yes`).
fn refused(err: lexopt::Error) -> CliError {
    match err {
        lexopt::Error::UnexpectedValue { option, value } => usage(format!(
            "{option} takes no value, and was given {}",
            value.to_string_lossy()
        )),
        other => usage(other.to_string()),
    }
}

/// Whether `args` ask for help (an option of `table` with the long name `help`), wherever it
/// stands and whatever else is wrong with them; the value of an option (`-o --help`) and an
/// argument after `--` are not asking.
pub(crate) fn asks_help<Id>(args: &[OsString], table: &[Opt<Id>]) -> bool {
    let mut parser = Parser::from_args(args.iter().cloned());
    // Each round takes at least one argument: the loop ends.
    for _ in 0..=args.len() {
        let arg = match parser.next() {
            Ok(Some(arg)) => arg,
            Ok(None) => return false,
            Err(_) => continue,
        };
        match find(table, &arg) {
            Some((opt, _)) if opt.long == "help" => return true,
            Some((opt, _)) if opt.value.is_some() => {
                let _ = parser.value();
            }
            _ => {}
        }
    }
    false
}

/// The help of `table`: one entry a line, the help starting in column `width + 2` (or on the
/// next line, for a name that does not leave a space before it).
pub(crate) fn help<Id>(table: &[Opt<Id>], width: usize) -> String {
    let mut text = String::new();
    let indent = " ".repeat(width + 2);
    for opt in table {
        let mut name = match opt.short {
            Some(c) => format!("-{c}, --"),
            None => "    --".to_string(),
        };
        if opt.negatable {
            name.push_str("[no-]");
        }
        name.push_str(opt.long);
        if let Some(value) = opt.value {
            name.push(' ');
            name.push_str(value);
        }
        let mut lines = opt.help.lines();
        let first = lines.next().unwrap_or("");
        if name.len() < width {
            text.push_str(&format!("  {name:width$}{first}\n"));
        } else {
            text.push_str(&format!("  {name}\n{indent}{first}\n"));
        }
        for line in lines {
            text.push_str(&format!("{indent}{line}\n"));
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Copy, Clone, Debug, PartialEq)]
    enum Id {
        Output,
        Number,
        Smooth,
        Help,
    }

    const TABLE: &[Opt<Id>] = &[
        Opt {
            id: Id::Output,
            short: Some('o'),
            long: "output",
            negatable: false,
            value: Some("FILE"),
            help: "write to FILE",
        },
        Opt {
            id: Id::Number,
            short: None,
            long: "u",
            negatable: false,
            value: Some("X"),
            help: "a number",
        },
        Opt {
            id: Id::Smooth,
            short: None,
            long: "smooth",
            negatable: true,
            value: None,
            help: "smooth\nor not",
        },
        Opt {
            id: Id::Help,
            short: Some('h'),
            long: "help",
            negatable: false,
            value: None,
            help: "show this help",
        },
    ];

    fn args(args: &[&str]) -> Vec<OsString> {
        args.iter().map(OsString::from).collect()
    }

    fn given(args_: &[&str]) -> Vec<(Id, bool, String, Option<String>)> {
        let lexed = lex(&args(args_), TABLE, "").unwrap();
        lexed
            .given
            .into_iter()
            .map(|g| {
                (
                    g.id,
                    g.on,
                    g.flag,
                    g.value.map(|v| v.into_string().unwrap()),
                )
            })
            .collect()
    }

    #[test]
    fn values_attached_or_apart() {
        for line in [
            &["--u=2.5"][..],
            &["--u", "2.5"],
            &["-o/dev/null", "--u", "2.5"],
        ] {
            let seen = given(line);
            assert!(
                seen.contains(&(Id::Number, true, "--u".into(), Some("2.5".into()))),
                "{line:?}"
            );
        }
        for line in [
            &["-o/dev/null"][..],
            &["-o", "/dev/null"],
            &["--output=/dev/null"],
        ] {
            let seen = given(line);
            assert_eq!(seen.len(), 1, "{line:?}");
            assert_eq!(seen[0].0, Id::Output);
            assert_eq!(seen[0].3.as_deref(), Some("/dev/null"), "{line:?}");
        }
        assert_eq!(given(&["--u", "-1"])[0].3.as_deref(), Some("-1"));
        assert_eq!(given(&["-o"])[0].3, None, "the command line ended");
        assert_eq!(
            given(&["--no-smooth", "--smooth"])
                .iter()
                .map(|g| g.1)
                .collect::<Vec<_>>(),
            [false, true]
        );
    }

    #[test]
    fn operands_and_the_end_of_options() {
        let lexed = lex(&args(&["-", "a.txt", "--", "--u", "-o"]), TABLE, "").unwrap();
        assert!(lexed.given.is_empty());
        assert_eq!(lexed.operands, args(&["-", "a.txt", "--u", "-o"]));
        for bad in [&["--bogus"][..], &["-x"], &["--smooth=yes"], &["--no-u"]] {
            let err = lex(&args(bad), TABLE, "").unwrap_err();
            assert_eq!(err.exit_code(), 2, "{bad:?}");
        }
        let said = lex(&args(&["--frob"]), TABLE, "score: ")
            .unwrap_err()
            .to_string();
        assert!(said.starts_with("score: unknown option --frob"), "{said}");
        assert!(!said.contains("did you mean"), "{said}");
    }

    /// A typo of a long option is answered with the option it likely means (a power user's
    /// review: `--quite`), the nearest within a third of its length, and none when nothing is
    /// that near.
    #[test]
    fn a_mistyped_option_gets_the_nearest_one() {
        for (typed, meant) in [
            ("--outptu", "--output"),
            ("--no-smoth", "--no-smooth"),
            ("--smoth", "--smooth"),
        ] {
            let said = lex(&args(&[typed]), TABLE, "").unwrap_err().to_string();
            assert!(
                said.contains(&format!("(did you mean {meant}?)")),
                "{typed}: {said}"
            );
        }
        assert_eq!(edits("kitten", "sitting"), 3);
        assert_eq!(edits("", "abc"), 3);
    }

    #[test]
    #[cfg(unix)]
    fn operands_need_not_be_utf8() {
        use std::os::unix::ffi::OsStringExt;
        let name = OsString::from_vec(b"caf\xe9.txt".to_vec());
        let lexed = lex(&[name.clone(), "-o".into(), name.clone()], TABLE, "").unwrap();
        assert_eq!(lexed.operands, std::slice::from_ref(&name));
        assert_eq!(lexed.given[0].value.as_ref(), Some(&name));
    }

    #[test]
    fn help_is_asked_wherever_it_stands_but_not_as_a_value() {
        assert!(asks_help(&args(&["in.txt", "--help"]), TABLE));
        assert!(asks_help(&args(&["--bogus", "-h"]), TABLE));
        assert!(asks_help(&args(&["--smooth=x", "--help"]), TABLE));
        assert!(!asks_help(&args(&["-o", "--help"]), TABLE));
        assert!(!asks_help(&args(&["--", "--help"]), TABLE));
        assert!(!asks_help(&args(&["in.txt"]), TABLE));
    }

    #[test]
    fn the_help_is_made_from_the_table() {
        assert_eq!(
            help(TABLE, 12),
            "  -o, --output FILE\n              write to FILE\n\
             \x20     --u X   a number\n\
             \x20 \x20   --[no-]smooth\n              smooth\n              or not\n\
             \x20 -h, --help  show this help\n"
        );
    }
}
