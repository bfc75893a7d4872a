//! Nothing but its build script: it writes the chip's `memory.x` into `OUT_DIR` and puts
//! that folder on the linker search path of the firmware that depends on it.
#![no_std]
