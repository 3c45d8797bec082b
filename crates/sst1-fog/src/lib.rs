//! sst1-fog (in progress)
