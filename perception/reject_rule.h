#pragma once
/// @file
/// The reject rule, alone so that the cell's sorting rules use it without the model's headers.

namespace sortcell::perception {

/// Whether a recognition with `confidence` is rejected at `reject_below` (a calibrated confidence in
/// [0, 1]; 0 rejects nothing): the one reject rule of every command and of the cell's sorting rules.
inline bool Rejected(double confidence, double reject_below) { return confidence < reject_below; }

}  // namespace sortcell::perception
