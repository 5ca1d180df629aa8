//! The command line's flags that set a scene parameter take their help
//! (what the parameter does, its range and default) from the core's table
//! ([`shadelab_core::params`]), written once for the scene file, the flags
//! and the page. Clap's derive takes only constant help, so the help is set
//! on the derived command here.

use clap::{CommandFactory, FromArgMatches};
use shadelab_core::params;

use crate::cli::Cli;

impl Cli {
    /// Parses the process's arguments with [`Cli::command_with_params`].
    ///
    /// # Errors
    /// Clap's error, help or version, for the caller to print.
    pub fn try_parse_with_params() -> Result<Cli, clap::Error> {
        let matches = Cli::command_with_params().try_get_matches()?;
        Cli::from_arg_matches(&matches)
    }

    /// The command line, with the help of every flag that sets a scene
    /// parameter taken from the core's table ([`params`]): what it does,
    /// its range and its default, written once for the scene file, the
    /// flags and the page.
    pub fn command_with_params() -> clap::Command {
        let mut command = Cli::command();
        let names: Vec<String> = command
            .get_subcommands()
            .map(|s| s.get_name().to_owned())
            .collect();
        for name in names {
            command = command.mut_subcommand(name, |mut sub| {
                for &(id, key, note) in PARAM_FLAGS {
                    if sub.get_arguments().any(|a| a.get_id() == id) {
                        let help = format!("{}{note}", params::get(key).long_help());
                        sub = sub.mut_arg(id, |a| a.help(help));
                    }
                }
                sub
            });
        }
        command
    }
}

/// The override flags (by their field's name) whose help is a scene
/// parameter's: that parameter's key, and what the flag adds to it.
const PARAM_FLAGS: &[(&str, &str, &str)] = &[
    ("detail", "model.detail", ""),
    ("crease_angle", "model.crease_angle", ""),
    ("ambient", "ambient.color", " (R,G,B)"),
    ("ambient_intensity", "ambient.intensity", ""),
    (
        "light_pos",
        "lights.position",
        " (X,Y,Z; the first light, made a point light)",
    ),
    ("light_color", "lights.color", " (R,G,B; the first light)"),
    ("light_intensity", "lights.intensity", " (the first light)"),
    (
        "light_attenuation",
        "lights.attenuation",
        " (CONSTANT,LINEAR,QUADRATIC; the first light)",
    ),
    ("ka", "material.ka", " (R,G,B)"),
    ("kd", "material.kd", " (R,G,B)"),
    ("ks", "material.ks", " (R,G,B)"),
    ("shininess", "material.shininess", ""),
    ("yaw", "render.yaw", ""),
    ("pitch", "render.pitch", ""),
    ("background", "render.background", " (R,G,B)"),
    ("fixed_point", "render.fixed_point_bits", ""),
    ("palette", "render.palette_shades", ""),
    ("palette_offset", "render.palette_offset", ""),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_parameter_flag_takes_its_help_from_the_table() {
        let command = Cli::command_with_params();
        command.clone().debug_assert();
        let render = command.find_subcommand("render").expect("render");
        for &(id, key, _) in PARAM_FLAGS {
            let arg = render
                .get_arguments()
                .find(|a| a.get_id() == id)
                .unwrap_or_else(|| panic!("render has no flag {id}"));
            let help = arg.get_help().expect("a help").to_string();
            assert!(help.starts_with(&params::get(key).long_help()), "{help}");
        }
    }
}
