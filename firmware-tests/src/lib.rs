//! Port layer for hardware-behaviour tests (in progress)
