//! Opening and closing a recording.

use anyhow::{Context, Result};
use rerun::{RecordingStream, RecordingStreamBuilder};

use crate::target::Target;

/// Application id of every rins recording (Rerun groups recordings by it; no dots allowed).
pub const APP_ID: &str = "rins";

/// An open recording. Call [`Recorder::finish`] at the end: it flushes and closes the stream,
/// which writes the `.rrd` footer; a recording dropped without it may be truncated.
pub struct Recorder {
    rec: RecordingStream,
    target: Target,
}

impl Recorder {
    /// Opens `target`, naming the recording `name` (shown in the viewer's recording list).
    pub fn open(target: &Target, name: &str) -> Result<Self> {
        let builder = RecordingStreamBuilder::new(APP_ID).recording_name(name);
        let rec = match target {
            Target::Save(path) => {
                if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
                    std::fs::create_dir_all(dir)
                        .with_context(|| format!("cannot create {}", dir.display()))?;
                }
                builder
                    .save(path)
                    .with_context(|| format!("cannot create the recording {}", path.display()))?
            }
            Target::Spawn => builder.spawn().context(
                "cannot spawn the Rerun viewer (is `rerun` on PATH? pip install rerun-sdk==0.36.3)",
            )?,
            Target::Connect(url) => builder
                .connect_grpc_opts(url.clone())
                .with_context(|| format!("cannot connect to a Rerun viewer at {url}"))?,
        };
        Ok(Self {
            rec,
            target: target.clone(),
        })
    }

    /// The stream, for loggers.
    pub fn stream(&self) -> &RecordingStream {
        &self.rec
    }

    /// Where the recording goes.
    pub fn target(&self) -> &Target {
        &self.target
    }

    /// Flushes everything and closes the stream.
    pub fn finish(self) -> Result<()> {
        self.rec
            .flush_blocking()
            .context("flushing the Rerun recording")?;
        self.rec.disconnect();
        Ok(())
    }
}
