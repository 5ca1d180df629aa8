//! The command line's flags that set a scene parameter, made from the
//! core's table ([`shadelab_core::params`]): each parameter with a `flag`
//! becomes `--flag`, with the table's help, range and default as its help,
//! its kind's syntax (`R,G,B`, `X,Y,Z`, a number) and its range checked as
//! the value is read, and the value written into the scene file by the
//! parameter's key. A new parameter in the table is a new flag here with
//! no line of this file changed.
//!
//! Clap's derive cannot make arguments from a table, so [`ParamFlags`]
//! implements [`clap::Args`] by hand and is flattened into the derived
//! [`crate::cli::SceneOverrides`].

use clap::{Arg, ArgAction, ArgMatches, Args, FromArgMatches};
use shadelab_core::params::{self, Kind, Param};
use shadelab_io::SceneFile;

/// The parameters given on the command line, in the table's order, each
/// with its value as the scene file would hold it.
#[derive(Debug, Clone, Default)]
pub struct ParamFlags {
    given: Vec<(&'static Param, toml::Value)>,
}

/// The table's parameters that have a flag.
fn flagged() -> impl Iterator<Item = &'static Param> {
    params::all().iter().filter(|p| !p.flag.is_empty())
}

impl ParamFlags {
    /// Whether the flag of the parameter with scene-file key `key` was given.
    pub fn has(&self, key: &str) -> bool {
        self.given.iter().any(|(p, _)| p.key == key)
    }

    /// These flags with the parameter of key `key` set to `value`, as if
    /// given (`accuracy` renders each detail in turn this way).
    pub fn with(&self, key: &str, value: toml::Value) -> ParamFlags {
        let param = params::get(key);
        let mut given: Vec<_> = self
            .given
            .iter()
            .filter(|(p, _)| p.key != key)
            .cloned()
            .collect();
        given.push((param, value));
        given.sort_by_key(|(p, _)| order(p));
        ParamFlags { given }
    }

    /// Writes every given flag into `scene` under its parameter's key. A
    /// key whose parameter needs this one (`render.palette_offset` needs
    /// `render.palette_shades`) is removed when it was not given too: the
    /// file's offset belonged to the file's palette. A light's position
    /// makes it a point light.
    ///
    /// # Errors
    /// The scene's error for a key the format does not hold (a mistake in
    /// the table, which the tests go through).
    pub fn apply(&self, scene: &mut SceneFile) -> Result<(), shadelab_io::SceneError> {
        let mut edits = Vec::new();
        for (param, value) in &self.given {
            edits.push((param.key, Some(value.clone())));
            for dependent in params::all().iter().filter(|q| q.needs == param.key) {
                if !self.has(dependent.key) {
                    edits.push((dependent.key, None));
                }
            }
            if param.key == "lights.position" {
                edits.push(("lights.kind", Some(toml::Value::from("point"))));
                edits.push(("lights.direction", None));
            }
        }
        if edits.is_empty() {
            return Ok(());
        }
        scene.edit(&edits)
    }
}

/// A parameter's place in the table.
fn order(param: &Param) -> usize {
    params::all()
        .iter()
        .position(|p| p.key == param.key)
        .unwrap_or(usize::MAX)
}

impl FromArgMatches for ParamFlags {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let given = flagged()
            .filter_map(|p| match p.kind {
                Kind::Bool => matches
                    .get_flag(p.key)
                    .then_some((p, toml::Value::Boolean(true))),
                _ => matches
                    .get_one::<toml::Value>(p.key)
                    .map(|v| (p, v.clone())),
            })
            .collect();
        Ok(ParamFlags { given })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = ParamFlags::from_arg_matches(matches)?;
        Ok(())
    }
}

impl Args for ParamFlags {
    fn augment_args(mut command: clap::Command) -> clap::Command {
        for param in flagged() {
            command = command.arg(arg(param));
        }
        command
    }

    fn augment_args_for_update(command: clap::Command) -> clap::Command {
        ParamFlags::augment_args(command)
    }
}

/// The flag of `param`: its name, help and value's syntax from the table.
fn arg(param: &'static Param) -> Arg {
    let arg = Arg::new(param.key)
        .long(param.flag)
        .help(help(param))
        .required(false);
    let arg = match param.needs {
        "" => arg,
        needed => arg.requires(needed),
    };
    match param.kind {
        Kind::Bool => arg.action(ArgAction::SetTrue),
        _ => arg
            .action(ArgAction::Set)
            .value_name(value_name(param))
            .allow_hyphen_values(true)
            .value_parser(move |text: &str| {
                parse(param, text).map_err(|e| format!("{}: {e}", param.key))
            }),
    }
}

/// The table's help, with the syntax of three numbers and which light.
fn help(param: &Param) -> String {
    let mut help = param.long_help();
    if param.key.starts_with("lights.") {
        help.push_str(if param.key == "lights.position" {
            " (the first light, made a point light)"
        } else {
            " (the first light)"
        });
    }
    help
}

/// What the flag's value is, in help: the unit (`BITS`), the three parts
/// (`RED,GREEN,BLUE`) or the kind (`NUMBER`).
fn value_name(param: &Param) -> String {
    if !param.parts.is_empty() {
        param.parts.join(",").to_uppercase()
    } else if !param.unit.is_empty() {
        param.unit.to_uppercase()
    } else if param.kind == Kind::Integer {
        "WHOLE".to_owned()
    } else {
        "NUMBER".to_owned()
    }
}

/// `text` as a value of `param`, in range, as the scene file holds it.
fn parse(param: &Param, text: &str) -> Result<toml::Value, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let three = || {
        if parts.len() == 3 {
            Ok(())
        } else {
            Err(format!(
                "expected {} (three comma-separated numbers), got {text:?}",
                value_name(param)
            ))
        }
    };
    let float = |s: &str| {
        s.parse::<f32>()
            .map_err(|_| format!("{s:?} is not a number"))
    };
    let whole = |s: &str| {
        s.parse::<i64>()
            .map_err(|_| format!("{s:?} is not a whole number"))
    };
    match param.kind {
        Kind::Number => Ok(toml::Value::Float(f64::from(
            param.check(float(text.trim())?)?,
        ))),
        Kind::Integer => Ok(toml::Value::Integer(
            param.check_whole(whole(text.trim())?)?,
        )),
        Kind::Rgb => {
            three()?;
            let c = [whole(parts[0])?, whole(parts[1])?, whole(parts[2])?];
            param.check_rgb(c)?;
            Ok(toml::Value::Array(c.map(toml::Value::Integer).to_vec()))
        }
        Kind::Vec3 => {
            three()?;
            let v = [float(parts[0])?, float(parts[1])?, float(parts[2])?];
            let v = param.check_vec3(v)?;
            Ok(toml::Value::Array(
                v.map(|c| toml::Value::Float(f64::from(c))).to_vec(),
            ))
        }
        Kind::Bool | Kind::Text => Err(format!("--{} takes no value", param.flag)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::Cli;
    use clap::CommandFactory;

    #[test]
    fn every_flagged_parameter_is_a_flag_of_every_scene_command_with_the_tables_help() {
        let command = Cli::command();
        command.clone().debug_assert();
        let scene_commands: Vec<_> = command
            .get_subcommands()
            .filter(|s| s.get_arguments().any(|a| a.get_id() == "no_cull"))
            .collect();
        assert!(scene_commands.len() >= 7, "{}", scene_commands.len());
        for sub in scene_commands {
            for param in flagged() {
                let arg = sub
                    .get_arguments()
                    .find(|a| a.get_long() == Some(param.flag))
                    .unwrap_or_else(|| panic!("{} has no --{}", sub.get_name(), param.flag));
                let help = arg.get_help().expect("a help").to_string();
                assert!(help.starts_with(&param.long_help()), "{help}");
            }
        }
    }

    #[test]
    fn values_are_read_by_kind_and_checked_against_the_range() {
        let p = params::get("material.ks");
        assert_eq!(
            parse(p, "1, 2,3").unwrap(),
            toml::Value::Array(vec![1.into(), 2.into(), 3.into()])
        );
        assert!(parse(p, "1,2,256").unwrap_err().contains("0..=255"));
        assert!(parse(p, "1,2").unwrap_err().contains("RED,GREEN,BLUE"));
        let p = params::get("lights.attenuation");
        assert!(parse(p, "1,-0.5,0")
            .unwrap_err()
            .contains("each 0..=1000000"));
        let p = params::get("material.shininess");
        assert_eq!(parse(p, "12.5").unwrap(), toml::Value::Float(12.5));
        assert!(parse(p, "-1").unwrap_err().contains("0..=10000"));
        assert!(parse(p, "NaN").is_err());
        let p = params::get("render.fixed_point_bits");
        assert!(parse(p, "40").unwrap_err().contains("1..=30 bits"));
        assert!(parse(p, "8.5").unwrap_err().contains("not a whole number"));
    }
}
