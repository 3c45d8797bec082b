//! A build without the `window` feature: no window ever opens.

use crate::{Event, Frame, NoWindow};

/// A window, which this build cannot open: the type has no values.
#[derive(Debug)]
pub enum Window {}

impl Window {
    /// Always `Err`: this build has no window.
    pub fn open(_title: &str) -> Result<Self, NoWindow> {
        Err(NoWindow(
            "this build has no window (it was built without the `window` feature)".into(),
        ))
    }

    /// Never called: there is no window.
    pub fn show(&self, _frame: Frame) {
        match *self {}
    }

    /// Never called: there is no window.
    pub fn set_title(&self, _title: &str) {
        match *self {}
    }

    /// Never called: there is no window.
    pub fn next_event(&self) -> Option<Event> {
        match *self {}
    }

    /// Never called: there is no window.
    pub fn try_event(&self) -> Option<Event> {
        match *self {}
    }
}
