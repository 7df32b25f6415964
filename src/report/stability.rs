//! Stability campaign (see below).
