//! Files and the commands around them: [`pointfile`] reads a user's PLY or OBJ and writes
//! coloured PLYs, [`animation`] writes the animated glTF of a pair's parts, and
//! [`commands`] is what `model infer` and `model animate` do, as library calls.

pub mod animation;
pub mod commands;
pub mod pointfile;
