//! sst1-dither (in progress)
