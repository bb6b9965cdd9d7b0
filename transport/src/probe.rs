//! Named points of the transport's lifecycle, reported to a probe as they are reached. The
//! chaos tests stop a process at one of them and kill it there (kill -9 at each lifecycle
//! stage); the detection stages time how fast the survivor noticed.

/// A lifecycle point of the plant (`Plant…`) or the navigator (`Nav…`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Plant: waiting for a navigator to connect, before batch `seq` (0: the first).
    PlantWaiting(u64),
    /// Plant: a navigator is connected, no batch sent yet.
    PlantConnected,
    /// Plant: batch `seq` is sent, its acknowledgement awaited (lockstep).
    PlantAwaitingAck(u64),
    /// Plant: about to resend batch `seq` to a navigator that (re)joined.
    PlantResending(u64),
    /// Plant: the end-of-run batch `seq` is sent.
    PlantEndSent(u64),
    /// Plant: the navigator was found dead, gone or stalled with batch `seq` in flight.
    PlantLostNavigator(u64),
    /// Navigator: hello sent, nothing received yet.
    NavJoined,
    /// Navigator: batch `seq` received and integrated, not yet acknowledged.
    NavReceived(u64),
    /// Navigator: the end-of-run batch `seq` received, not yet acknowledged.
    NavEndReceived(u64),
    /// Navigator: the plant was found dead, gone or stalled; `seq` is the next batch expected.
    NavLostPlant(u64),
}

impl Stage {
    /// Parses `name` or `name:seq` as printed by [`Stage::label`].
    pub fn parse(s: &str) -> Option<Self> {
        let (name, seq) = match s.split_once(':') {
            Some((n, q)) => (n, q.parse().ok()?),
            None => (s, 0),
        };
        Some(match name {
            "plant-waiting" => Self::PlantWaiting(seq),
            "plant-connected" => Self::PlantConnected,
            "plant-awaiting-ack" => Self::PlantAwaitingAck(seq),
            "plant-resending" => Self::PlantResending(seq),
            "plant-end-sent" => Self::PlantEndSent(seq),
            "plant-lost-navigator" => Self::PlantLostNavigator(seq),
            "nav-joined" => Self::NavJoined,
            "nav-received" => Self::NavReceived(seq),
            "nav-end-received" => Self::NavEndReceived(seq),
            "nav-lost-plant" => Self::NavLostPlant(seq),
            _ => return None,
        })
    }

    /// `name:seq`.
    pub fn label(&self) -> String {
        let (name, seq) = match *self {
            Self::PlantWaiting(s) => ("plant-waiting", s),
            Self::PlantConnected => ("plant-connected", 0),
            Self::PlantAwaitingAck(s) => ("plant-awaiting-ack", s),
            Self::PlantResending(s) => ("plant-resending", s),
            Self::PlantEndSent(s) => ("plant-end-sent", s),
            Self::PlantLostNavigator(s) => ("plant-lost-navigator", s),
            Self::NavJoined => ("nav-joined", 0),
            Self::NavReceived(s) => ("nav-received", s),
            Self::NavEndReceived(s) => ("nav-end-received", s),
            Self::NavLostPlant(s) => ("nav-lost-plant", s),
        };
        format!("{name}:{seq}")
    }
}

#[cfg(test)]
mod tests {
    use super::Stage;

    #[test]
    fn labels_parse_back() {
        for s in [
            Stage::PlantWaiting(4),
            Stage::PlantConnected,
            Stage::PlantAwaitingAck(7),
            Stage::PlantResending(3),
            Stage::PlantEndSent(9),
            Stage::PlantLostNavigator(2),
            Stage::NavJoined,
            Stage::NavReceived(5),
            Stage::NavEndReceived(11),
            Stage::NavLostPlant(4),
        ] {
            assert_eq!(Stage::parse(&s.label()), Some(s));
        }
        assert_eq!(Stage::parse("nav-received:x"), None);
    }
}
