//! sst1-ncc (in progress)
