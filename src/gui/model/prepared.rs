//! What a preparation made ready for a new scene (the job that makes it is
//! `jobs::prepare`).

use crate::identify::PreparedModel;
use crate::model::road::RoadProfile;

/// What was prepared.
#[derive(Debug, Clone, PartialEq)]
pub enum Prepared {
    /// A whole model (the scene, its modes, its road): for a restart.
    Model(Box<PreparedModel>),
    /// A road profile: for a live road edit.
    Road(RoadProfile),
}
