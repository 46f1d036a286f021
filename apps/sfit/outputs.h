// Output formats chosen by the -o extension: the library's dispatch (sfit/files.h), under the
// names the commands use.
#pragma once

#include <string>

#include "sfit/files.h"

namespace sfit::cli {

using files::check_output_extension;
using files::check_output_options;
using files::output_extensions;
using files::OutputContext;
using files::write_output;
using io::extension_of;

}  // namespace sfit::cli
