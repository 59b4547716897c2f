//! Files: [`pointfile`] reads a user's PLY or OBJ and writes coloured PLYs, [`animation`]
//! writes the animated glTF of a pair's parts.

pub mod animation;
pub mod pointfile;
