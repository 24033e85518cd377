//! Reading models and matrices: linear-DAE pencil files, Matrix Market matrices.
