//! [`Backend::model_box`](crate::draw::Backend::model_box) over the ZeroMQ remote API: the
//! object's handle by its name, then its six model bounding-box parameters (21..26) by one
//! request.

use super::ZmqBackend;
use crate::draw::{BackendError, BoundingBox};
use crate::zmq_api::cbor::{self, int};
use vrep_maze_core::coppelia::OBJFLOATPARAM_MODELBBOX;

impl ZmqBackend {
    /// The model box of the object `name`; `None` when there is none or a parameter is not
    /// answered.
    pub(super) fn read_model_box(
        &mut self,
        name: &str,
    ) -> Result<Option<BoundingBox>, BackendError> {
        let Some(handle) = self.handle_of(name)? else {
            return Ok(None);
        };
        let calls: Vec<(&str, Vec<ciborium::Value>)> = (0..6)
            .map(|k| {
                let param = OBJFLOATPARAM_MODELBBOX + k;
                (
                    "sim.getObjectFloatParam",
                    vec![int(handle.into()), int(param.into())],
                )
            })
            .collect();
        let mut v = [0.0; 6];
        for (slot, outcome) in v.iter_mut().zip(self.client.read_all(&calls)?) {
            let Some(value) = outcome.ok().and_then(|o| o.first().and_then(cbor::number)) else {
                return Ok(None);
            };
            *slot = value;
        }
        Ok(Some(BoundingBox {
            min: [v[0], v[1], v[2]],
            max: [v[3], v[4], v[5]],
        }))
    }
}
