// Typed errors of the tissuemesh libraries.
//
// The libraries never print and never exit: they throw one of these and `app/` maps them to exit
// codes (InputError, OutputError -> 2: the user can fix it; everything else -> 1: internal failure).
// Messages name the culprit (file, config key, label, tissue) so that they can be shown as they are.
#pragma once

#include <stdexcept>
#include <string>

namespace tissuemesh {

/// Base of every error the libraries throw on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input: unreadable/corrupt/truncated file, unsupported pixel type, invalid config key or value,
/// unmapped label, empty tissue. The user can fix it.
class InputError : public Error {
 public:
  using Error::Error;
};

/// An output cannot be written (unwritable directory, disk full). The user can fix it.
class OutputError : public Error {
 public:
  using Error::Error;
};

/// The mesher failed on valid input (e.g. CGAL produced no cells). A bug or a limitation.
class MeshingError : public Error {
 public:
  using Error::Error;
};

/// The solver failed on a valid model.
class SolverError : public Error {
 public:
  using Error::Error;
};

}  // namespace tissuemesh
