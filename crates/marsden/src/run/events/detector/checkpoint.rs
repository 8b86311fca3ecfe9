//! What an event detector carries from one step to the next, for a checkpoint of the run
//! ([`EventDetector::checkpoint`], [`EventDetector::restore`]).

use super::{EventDetector, Point};
use crate::error::{Error, InputError};
use crate::mechanics::Lagrangian;
use crate::run::events::{EventFunction, EventRecord};

/// What an [`EventDetector`] carries from one step to the next ([`EventDetector::checkpoint`]).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DetectorCheckpoint {
    before: Point,
    g_before: Vec<f64>,
    crossings: Vec<usize>,
    records: Vec<EventRecord>,
}

impl<L: Lagrangian, G: EventFunction> EventDetector<'_, L, G> {
    /// What the detector carries to the next step, for a checkpoint of the run: the state the
    /// next step starts from with its velocities and `g` there, the crossings counted and the
    /// records located so far. When no event reads `v` the velocities are not carried (they are
    /// recomputed from `q`, `p` at a crossing) and the checkpoint holds zeros in their place.
    pub fn checkpoint(&self) -> DetectorCheckpoint {
        let mut before = self.before.clone();
        if !self.velocities_every_step {
            before.v.fill(0.0);
        }
        DetectorCheckpoint {
            before,
            g_before: self.g_before.clone(),
            crossings: self.crossings.clone(),
            records: self.records.clone(),
        }
    }

    /// Restores a [`EventDetector::checkpoint`] of a detector of the same events: the next
    /// step is looked at as the checkpointed detector would have.
    ///
    /// # Errors
    /// [`InputError::DimensionMismatch`] if the checkpoint has another number of events or
    /// coordinates; the detector is then unchanged.
    pub fn restore(&mut self, checkpoint: &DetectorCheckpoint) -> Result<(), Error> {
        let sizes = [
            (
                "checkpoint events",
                self.g_before.len(),
                checkpoint.g_before.len(),
            ),
            (
                "checkpoint coordinates",
                self.before.q.len(),
                checkpoint.before.q.len(),
            ),
        ];
        for (what, expected, found) in sizes {
            if expected != found {
                return Err(Error::Input(InputError::DimensionMismatch {
                    what,
                    expected,
                    found,
                }));
            }
        }
        self.before.clone_from(&checkpoint.before);
        self.g_before.clone_from(&checkpoint.g_before);
        self.crossings.clone_from(&checkpoint.crossings);
        self.records.clone_from(&checkpoint.records);
        // A checkpoint is taken after the step is shown: no sign change is left to locate.
        (self.ending, self.pending) = (None, false);
        Ok(())
    }
}
