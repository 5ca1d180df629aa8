//! `shadelab explain`: the pixel inspector as text.

use std::io::Write;

use shadelab_core::limits::RENDER_BYTES_PER_PIXEL;
use shadelab_core::Shading;
use shadelab_lab::{inspect, inspection_text, Texts};

use crate::cli::ExplainArgs;
use crate::lab::load;
use crate::{input_error, output_error, Failure};

/// Prints, for the pixel and each method, what the scanline rasterizer did.
pub fn run(args: &ExplainArgs) -> Result<(), Failure> {
    let loaded = load(
        args.scene.as_deref(),
        &args.overrides,
        Some((480, 480)),
        None,
    )?;
    loaded.check_memory("explain", RENDER_BYTES_PER_PIXEL)?;
    let (x, y) = args.pixel;
    let options = &loaded.options;
    if x >= options.width || y >= options.height {
        return Err(input_error(anyhow::anyhow!(
            "pixel ({x}, {y}) is outside the {}x{} image",
            options.width,
            options.height
        )));
    }
    let methods: Vec<Shading> = match args.shading {
        Some(s) => vec![s],
        None => Shading::ALL.to_vec(),
    };
    let inspection = inspect(&loaded.scene, options, x, y, &methods).map_err(input_error)?;
    let text = inspection_text(&inspection, &Texts::new(args.lang.into()));
    std::io::stdout()
        .lock()
        .write_all(text.as_bytes())
        .map_err(output_error)
}
