//! `generator render`: multi-view images of objects in several articulation states.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use renderer::cameras::{self, Placement};
use renderer::layout::{write_render, Layout};
use renderer::{RenderConfig, RenderJob};

use crate::commands::args::Selection;
use crate::commands::objects::{progress_bar, selected_objects};

/// The options of `generator render`.
#[derive(Debug, clap::Args)]
pub(crate) struct RenderArgs {
    #[command(flatten)]
    pub selection: Selection,
    /// Folder layout: native (ours: RGB, depth, label and normal images, cameras and joints
    /// as JSON), paris (what PARIS loads), dta (DigitalTwinArt) or artgs (ArtGS);
    /// docs/FORMAT.md, "Renders".
    #[arg(long, default_value = "native", value_parser = parse_layout)]
    pub layout: Layout,
    /// TOML file with render settings (any field of docs/FORMAT.md's render settings);
    /// the flags below override it.
    #[arg(long, value_name = "FILE")]
    pub render_config: Option<PathBuf>,
    /// Cameras per state [default: 24].
    #[arg(long, value_name = "V")]
    pub views: Option<u32>,
    /// Image width, pixels [default: 640].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height, pixels [default: 480].
    #[arg(long)]
    pub height: Option<u32>,
    /// Vertical field of view, degrees [default: 40].
    #[arg(long, value_name = "DEG")]
    pub fov: Option<f64>,
    /// Where the cameras stand: sphere or hemisphere (upper, +y up) [default: sphere].
    #[arg(long)]
    pub placement: Option<Placement>,
    /// Articulation states per object [default: 2; the paris, dta and artgs layouts take 2].
    #[arg(long)]
    pub states: Option<u32>,
    /// Cameras from a JSON file instead ({"cameras": [{width, height, fx, fy, cx, cy,
    /// camera_to_world}]}, OpenCV axes, object frame; docs/FORMAT.md, "Renders").
    #[arg(long, value_name = "FILE")]
    pub cameras: Option<PathBuf>,
    /// Output folder [default: renders/<layout>]; refused if not empty, unless --force.
    #[arg(short, long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace the output folder's contents (only once the render is complete).
    #[arg(long)]
    pub force: bool,
    /// Print the resolved render settings as TOML and exit.
    #[arg(long)]
    pub print_config: bool,
}

/// Shown after the options of `render --help`.
pub(crate) const RENDER_EXAMPLES: &str = "Examples:
  generator render -n 5                                  5 test objects, renders/native
  generator render --layout paris -n 5 --out renders/paris   PARIS's load/ and data/ trees
  generator render --layout dta -n 5 --out renders/dta   DigitalTwinArt's object folders
  generator render --layout artgs -n 5                   ArtGS's data/ tree and arguments/
  generator render --assets models/ --views 64 --width 800 --height 800
  generator render --cameras rig.json -n 2               your own calibrated cameras";

fn parse_layout(s: &str) -> Result<Layout, String> {
    s.parse()
}

impl RenderArgs {
    /// The render settings: defaults, then --render-config, then the flags.
    fn config(&self) -> Result<RenderConfig> {
        let mut config = match &self.render_config {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .with_context(|| format!("reading {}", path.display()))?;
                toml::from_str(&text)
                    .with_context(|| format!("parsing render settings {}", path.display()))?
            }
            None => RenderConfig::default(),
        };
        macro_rules! set {
            ($($flag:ident => $field:ident),*) => { $(if let Some(v) = &self.$flag { config.$field = v.clone(); })* };
        }
        set!(views => views, width => width, height => height, fov => fov_y_deg, placement => placement, states => states);
        if let Some(states) = self.layout.states() {
            if self.states.is_some_and(|s| s != states) {
                bail!(
                    "the {} layout holds {states} states, not {}",
                    self.layout.as_str(),
                    config.states
                );
            }
            config.states = states;
        }
        Ok(config)
    }
}

/// `generator render`.
pub(crate) fn render_command(args: &RenderArgs) -> Result<()> {
    let config = args.config()?;
    if args.print_config {
        print!("{}", toml::to_string(&config).context("formatting the render settings")?);
        return Ok(());
    }
    config.validate().context("checking the render settings")?;
    let generator_config = args.selection.config()?;
    generator_config.validate().context("checking the config")?;
    let cameras = match &args.cameras {
        Some(path) => Some(cameras::read(path).context("reading the cameras")?),
        None => None,
    };
    let out =
        args.out.clone().unwrap_or_else(|| PathBuf::from("renders").join(args.layout.as_str()));
    let started = std::time::Instant::now();
    let objects = selected_objects(&args.selection, &generator_config, "rendered")?;
    let views = cameras.as_ref().map_or(config.views as usize, Vec::len);
    let total = objects.len() as u64 * u64::from(config.states) * views as u64;
    let bar = progress_bar(total, "views");
    bar.set_message(format!("rendering {}", out.display()));
    let seed = generator_config.seed;
    let jobs = objects
        .into_iter()
        .map(|object| RenderJob::new(&config, seed, object, cameras.as_deref(), args.layout));
    let rendered =
        write_render(&config, seed, jobs, args.layout, &out, args.force, &|n| bar.set_position(n))
            .with_context(|| format!("rendering into {}", out.display()))?;
    bar.finish_and_clear();
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "wrote {} views of {} objects ({} layout) to {} in {seconds:.2} s ({:.1} views/s)",
        rendered.views,
        rendered.objects.len(),
        args.layout.as_str(),
        out.display(),
        rendered.views as f64 / seconds
    );
    Ok(())
}
