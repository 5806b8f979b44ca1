//! A trace read into a scene: the lander's model with the sample's own parameters, the
//! surface it lands on, and the sketch drawn of it.

use super::sketch::Sketch;
use super::trace::Trace;
use crate::reference::Model;
use crate::slope::Surface;
use anyhow::bail;
use std::path::Path;

/// A trace file ready to be drawn.
pub struct Scene {
    /// The trace: its rows and what its metadata says.
    pub trace: Trace,
    /// The surface the sample lands on.
    pub surface: Surface,
    /// The lander's model, with the sample's own parameters.
    pub model: Model,
    /// The lander's shape in B.
    pub sketch: Sketch,
}

impl Scene {
    /// Reads the trace file at `path` (`Trace::read`) and derives the lander and the surface
    /// from the scenario and sample it stores; refuses a trace whose legs are not its
    /// scenario's.
    pub fn read(path: &Path) -> anyhow::Result<Scene> {
        let trace = Trace::read(path)?;
        let surface = Surface::of(&trace.sample);
        // With the sample's own parameters (a drawn CG height moves the footpads).
        let model = Model::new(&trace.scenario)
            .for_sample(&trace.sample)
            .into_owned();
        let sketch = Sketch::of(&model);
        if trace.legs != model.legs.len() {
            bail!(
                "{}: {} legs in its columns, {} in its scenario",
                path.display(),
                trace.legs,
                model.legs.len()
            );
        }
        Ok(Scene {
            trace,
            surface,
            model,
            sketch,
        })
    }
}
