//! [`Lease`] over the ZeroMQ remote API: the integer signal [`LEASE`], claimed,
//! read and released.

use ciborium::Value;

use super::ZmqBackend;
use crate::draw::backend::{Claimed, Lease};
use crate::draw::error::BackendError;
use crate::draw::record::CopyRecord;
use crate::draw::signals::LEASE;
use crate::zmq_api::cbor::{self, int};

/// The lease is the integer signal [`LEASE`] (a simulator without integer signals
/// answers with a remote error, and the run goes on unguarded).
impl Lease for ZmqBackend {
    /// Four calls sent together ([`Client::call_all`](crate::zmq_api::Client::call_all): one
    /// main-loop pass over protocol 1): read the holder, write the token, remove an older
    /// version's lease (which stops an older run drawing now), read the token back.
    fn claim(&mut self, token: i32) -> Result<Claimed, BackendError> {
        let name = |n: &str| Value::Text(n.into());
        let calls = [
            ("sim.getInt32Signal", vec![name(LEASE.name)]),
            (
                "sim.setInt32Signal",
                vec![name(LEASE.name), int(token.into())],
            ),
            ("sim.clearInt32Signal", vec![name(LEASE.old)]),
            ("sim.getInt32Signal", vec![name(LEASE.name)]),
        ];
        let mut read = Vec::with_capacity(2);
        for (k, outcome) in self.client.call_all(&calls)?.into_iter().enumerate() {
            let values = outcome?;
            if k == 0 || k == 3 {
                read.push(values.first().and_then(cbor::int32));
            }
        }
        Ok(Claimed {
            previous: read[0],
            read_back: read[1],
        })
    }

    fn holder(&mut self) -> Result<Option<i32>, BackendError> {
        let name = Value::Text(LEASE.name.into());
        let values = self.call("sim.getInt32Signal", vec![name])?;
        Ok(values.first().and_then(cbor::int32))
    }

    fn release(&mut self) -> Result<(), BackendError> {
        let name = Value::Text(LEASE.name.into());
        self.call("sim.clearInt32Signal", vec![name])?;
        Ok(())
    }

    fn unkept(&mut self) {
        self.signals_kept = false;
        self.record = Some(CopyRecord::default());
        self.record_changed = false;
    }
}
