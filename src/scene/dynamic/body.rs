//! The body of a validated dynamic scene, and what validating a body gives.

use std::sync::Arc;

use crate::model::dynamic::bar::BarBody;
use crate::model::dynamic::contact_model::ContactModel;
use crate::model::dynamic::plane_body::PlaneBody;

/// The body of a validated scene (the concrete type, for outputs and plots).
#[derive(Debug, Clone)]
pub enum SceneBody {
    Bar(Arc<BarBody>),
    Plane(Arc<PlaneBody>),
}

/// What the validation of a body gives: the body, its contact, and the initial displacement
/// and velocity in the body's unknowns.
pub(super) type BodyParts = (SceneBody, Option<ContactModel>, Vec<f64>, Vec<f64>);
