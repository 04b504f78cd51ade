// `erkn list` and `erkn tableau NAME (--v X | --series K | --poles VMAX)`.
#pragma once

namespace erkn::cli {

int list_command(int argc, char** argv);
int tableau_command(int argc, char** argv);

/// Loads the files of every `--methods-file F.json` pair (Method::load: a user's methods, checked
/// against the orders they claim) and removes the pairs from argv; returns the new argc.
int load_methods_files(int argc, char** argv);

/// Parses a finite number or throws erkn::Error naming the option and the bad text.
double parse_number(const char* option, const char* text);

}  // namespace erkn::cli
