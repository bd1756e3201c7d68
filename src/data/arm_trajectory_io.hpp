#pragma once
// The arm-flywheel trajectory in the primitive database style (HDF5, one group, schema in
// docs/primitive-format.md, section "arm-flywheel"). Same guarantees as primitive_io.hpp: the target is only
// ever replaced whole (temporary sibling + rename); RuntimeError on I/O failure; reading a missing, corrupt or
// wrongly shaped file/dataset throws InputError naming the file and dataset.
#include <string>

#include "data/arm_trajectory.hpp"
#include "data/file_image.hpp"

namespace centaur::data {

/// Write the group `tr.name` to `path`. append = false: a new file holding only this group; append = true: the
/// other groups of an existing file are kept (a group of the same name is replaced).
void writeArmTrajectory(const std::string& path, const ArmTrajectory& tr, bool append = false);

/// Read group `name` (default "arm-flywheel"), every dataset validated (docs/primitive-format.md, "Validation").
ArmTrajectory readArmTrajectory(const std::string& path, const std::string& name = "arm-flywheel");
ArmTrajectory readArmTrajectory(const FileImage& image, const std::string& name = "arm-flywheel");

}  // namespace centaur::data
