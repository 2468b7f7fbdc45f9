// OpenDriveContent: the whole-drive reader of a drive's format (see drive_content.h).
#include "host/drive/drive_content.h"

#include "host/drive/drive.h"

namespace lpir {

std::unique_ptr<DriveContent> OpenDriveContent(const std::string& path) {
  const DriveFormat format = DriveFormatOf(path);
  if (format == DriveFormat::kBagFolder) return OpenBagFolderContent(path);
  if (format == DriveFormat::kMcap) return OpenMcapContent(path);
  if (format == DriveFormat::kDb3) return OpenDb3Content(path);
  return OpenRos1BagContent(path);
}

}  // namespace lpir
