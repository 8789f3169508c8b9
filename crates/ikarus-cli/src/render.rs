//! `ikarus render`: figures that stand on their own, such as the plot of an ease curve.

use clap::{Args, Subcommand};

use ikarus::EaseKind;

use crate::ease_args::EaseArgs;
use crate::error::CliError;
use crate::picture::{Drawing, PictureArgs, PictureFormat, draw};

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
            let ease = args.ease.resolve(EaseKind::Parent)?;
            let out = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png])?.expect("--out is set");
            let bytes = draw(&Drawing::Ease(ease), out.format, args.picture.width, args.picture.height, &|_, _| {})?;
            out.commit(&bytes)
        }
    }
}
