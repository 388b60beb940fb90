//! [`Backend::model_box`](crate::draw::Backend::model_box) over the legacy remote API:
//! `simxGetObjectHandle`, then the six model bounding-box parameters (21..26) of
//! `simxGetObjectFloatParameter` in one request.

use super::LegacyBackend;
use crate::draw::{BackendError, BoundingBox};
use crate::legacy::command::{Command, read_i32};
use vrep_maze_core::coppelia::OBJFLOATPARAM_MODELBBOX;

impl LegacyBackend {
    /// The model box of the object `name`; `None` when there is none or a parameter is not
    /// answered.
    pub(super) fn read_model_box(
        &mut self,
        name: &str,
    ) -> Result<Option<BoundingBox>, BackendError> {
        let found = self.call(&[Command::GetObjectHandle(name.to_string())])?;
        let Some(handle) = found
            .first()
            .filter(|r| !r.remote_error)
            .and_then(|r| read_i32(&r.data, 0))
        else {
            return Ok(None);
        };
        let params: Vec<Command> = (0..6)
            .map(|k| Command::GetObjectFloatParam {
                handle,
                param: OBJFLOATPARAM_MODELBBOX + k,
            })
            .collect();
        let mut v = [0.0; 6];
        for (slot, reply) in v.iter_mut().zip(self.call(&params)?) {
            let Some(b) = reply.data.get(..4).filter(|_| !reply.remote_error) else {
                return Ok(None);
            };
            *slot = f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        }
        Ok(Some(BoundingBox {
            min: [v[0], v[1], v[2]],
            max: [v[3], v[4], v[5]],
        }))
    }
}
