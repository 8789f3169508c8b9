//! `ikarus render`: figures that stand on their own, such as the plot of an ease curve.

use clap::{Args, Subcommand};

use crate::ease_args::{EaseArg, EaseArgs};
use crate::error::CliError;
use crate::picture::{PictureArgs, PictureFormat, render_failed};

#[derive(Debug, Subcommand)]
pub enum RenderCommand {
    /// Plot an ease curve: position and velocity against time (the seed's Figure 10)
    Ease(RenderEaseArgs),
}

#[derive(Debug, Args)]
pub struct RenderEaseArgs {
    #[command(flatten)]
    pub ease: EaseArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
}

pub fn run(command: &RenderCommand) -> Result<(), CliError> {
    match command {
        RenderCommand::Ease(args) => {
            if args.picture.out.is_none() {
                return Err(CliError::input("--out: required: the file to draw to (.svg or .png)"));
            }
            let ease = args.ease.resolve(EaseArg::Parent)?;
            let out = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png])?.expect("--out is set");
            let svg = ikarus_render::ease_svg(&ease, args.picture.width, args.picture.height)
                .map_err(|e| render_failed(&e))?;
            let bytes = match out.format {
                PictureFormat::Png => ikarus_render::svg_to_png(&svg).map_err(|e| render_failed(&e))?,
                _ => svg.into_bytes(),
            };
            out.commit(&bytes)
        }
    }
}
