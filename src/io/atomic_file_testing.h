// For the tests of OutputBatch's roll-back only: a rename of a batch made to fail as if the
// system refused it (a rename that no check before it can foresee, e.g. a disk error).
#pragma once

namespace sfit::io::testing {

/// Makes the next OutputBatch::commit()'s rename number `k` (0-based, in staging order) fail
/// with errno `error`, once; k = -1 cancels.
void fail_rename_at(int k, int error);

}  // namespace sfit::io::testing
