// lpir_gseg._core._Drive: a recorded drive (host/drive/drive.h: .mcap, .db3, a ROS 2 bag folder,
// .bag, .bag.active) read message by message, for lpir_gseg.read_drive and the fleet; and the
// inputs rule (host/drive/inputs.h) the fleet shares with the command line. Reading and
// decoding release the GIL.
#include "host/drive/drive.h"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "host/drive/inputs.h"
#include "host/drive/pointcloud2.h"
#include "host/io/io_error.h"

namespace lpir::python {
namespace {

class PyDrive {
 public:
  PyDrive(py::handle path_arg, unsigned read_threads) : path_(PathArg(path_arg)) {
    py::gil_scoped_release nogil;
    reader_ = OpenDrive(path_, read_threads);
  }

  const std::string& path() const { return path_; }

  // (name, type, encoding, messages) per topic.
  std::vector<py::tuple> Topics() {
    std::vector<DriveTopic> topics;
    {
      py::gil_scoped_release nogil;
      topics = reader_->Topics();
    }
    std::vector<py::tuple> out;
    for (const DriveTopic& t : topics)
      out.push_back(py::make_tuple(t.name, t.type, t.encoding, t.messages));
    return out;
  }

  // DriveReader::ListingDamage and Notes: lists of sentences naming the file.
  std::vector<std::string> ListingDamage() {
    py::gil_scoped_release nogil;
    return reader_->ListingDamage();
  }
  std::vector<std::string> Notes() {
    py::gil_scoped_release nogil;
    return reader_->Notes();
  }

  uint64_t ChunkCount() {
    py::gil_scoped_release nogil;
    return reader_->ChunkCount();
  }
  bool ChunksIndexed() {
    py::gil_scoped_release nogil;
    return reader_->ChunksIndexed();
  }

  // `topic`, restricted to chunks first..last when first is not 0 (DriveReader::SelectChunks).
  void Select(const std::string& topic, uint64_t first, uint64_t last) {
    py::gil_scoped_release nogil;
    reader_->SelectTopic(topic);
    if (first != 0) reader_->SelectChunks(first, last);
  }

  // ("message", sequence, header stamp in ns, points, ring or None), ("damage", problem) or
  // ("end",). points (N, 4) float32 owns the cloud, ring included (CloudArray). A message
  // that does not decode (pointcloud2.h's rules) is ("damage", the IoError's text naming the
  // file and the message).
  py::tuple Next() {
    DriveMessage message;
    std::string problem;
    DriveStep step;
    Cloud cloud;
    int64_t stamp_ns = 0;
    {
      py::gil_scoped_release nogil;
      step = reader_->Next(&message, &problem);
      if (step == DriveStep::kMessage) {
        const std::string where =
            path_ + ": " + message.topic + " message " + std::to_string(message.sequence);
        try {
          const PointCloud2 msg =
              message.encoding == MessageEncoding::kCdr
                  ? ParseCdrPointCloud2(where, message.data.data(), message.data.size())
                  : ParseRos1PointCloud2(where, message.data.data(), message.data.size());
          stamp_ns = msg.stamp_ns();
          cloud = CloudFromPointCloud2(where, msg);
        } catch (const IoError& e) {
          step = DriveStep::kDamage;
          problem = e.what();
        }
      }
    }
    if (step == DriveStep::kEnd) return py::make_tuple("end");
    if (step == DriveStep::kDamage) return py::make_tuple("damage", problem);
    py::object ring = py::none();
    if (!cloud.ring.empty()) ring = VectorArray(std::vector<int32_t>(cloud.ring));
    return py::make_tuple("message", message.sequence, stamp_ns, CloudArray(std::move(cloud)),
                          ring);
  }

 private:
  std::string path_;
  std::unique_ptr<DriveReader> reader_;
};

}  // namespace

void BindDrive(py::module_& m) {
  py::class_<PyDrive>(m, "_Drive",
                      "_Drive(path, read_threads=0)\n--\n\nA recorded drive opened by its "
                      "extension (.mcap, .db3, .bag), its chunks decompressed ahead on "
                      "read_threads threads (0: the default); lpir_gseg.read_drive is the "
                      "public way in.")
      .def(py::init<py::handle, unsigned>(), py::arg("path"), py::arg("read_threads") = 0)
      .def_property_readonly("path", &PyDrive::path)
      .def("topics", &PyDrive::Topics,
           "topics()\n--\n\n(name, type, encoding, messages) for every topic of the drive.")
      .def("listing_damage", &PyDrive::ListingDamage,
           "listing_damage()\n--\n\nThe damaged parts topics() met, each naming the file (empty "
           "when it read the drive whole or from its index).")
      .def("notes", &PyDrive::Notes,
           "notes()\n--\n\nHow the drive is read where that is not the plain way (an unindexed "
           "ROS 1 bag scanned, a bag folder's files taken by their numbers).")
      .def("chunk_count", &PyDrive::ChunkCount,
           "chunk_count()\n--\n\nThe drive's chunks, numbered from 1 (0 for a .db3).")
      .def("chunks_indexed", &PyDrive::ChunksIndexed,
           "chunks_indexed()\n--\n\nWhether select finds a range's start from the drive's "
           "index, without reading the chunks before it.")
      .def("select", &PyDrive::Select, py::arg("topic"), py::arg("first_chunk") = 0,
           py::arg("last_chunk") = 0,
           "select(topic, first_chunk=0, last_chunk=0)\n--\n\nReads `topic` from its first "
           "message on, only those of chunks first_chunk..last_chunk (numbered from 1) when "
           "first_chunk is not 0, each with the sequence a whole reading gives it (OSError when "
           "the drive has no such topic or chunks).")
      .def("next", &PyDrive::Next,
           "next()\n--\n\n('message', sequence, stamp_ns, points, ring), ('damage', problem) "
           "or ('end',).");
  m.def(
      "is_drive_file", [](py::handle path) { return IsDriveFile(PathArg(path)); }, py::arg("path"),
      "is_drive_file(path)\n--\n\nTrue for the recorded drives' file names: .mcap, .db3, .bag, "
      ".bag.active.");
  m.def(
      "_list_inputs",
      [](const std::vector<py::handle>& given, bool recursive) {
        std::vector<std::string> paths;
        for (py::handle p : given) paths.push_back(PathArg(p));
        std::vector<SkippedInput> skipped;
        std::vector<RunInput> inputs;
        {
          py::gil_scoped_release nogil;
          inputs = ListInputs(paths, recursive, &skipped);
        }
        std::vector<py::tuple> listed, passed;
        for (const RunInput& in : inputs)
          listed.push_back(py::make_tuple(in.path, in.folder, in.drive));
        for (const SkippedInput& s : skipped) passed.push_back(py::make_tuple(s.path, s.why));
        return py::make_tuple(listed, passed);
      },
      py::arg("paths"), py::arg("recursive") = false,
      "_list_inputs(paths, recursive=False)\n--\n\n([(path, folder, is_drive)], [(skipped path, "
      "why)]): the inputs the paths name, as `lpir-gseg segment` lists them (host/drive/inputs.h:"
      " a bag folder one drive, another folder its clouds and drives in path order, with "
      "recursive its subfolders' too; folder: the folder given it was found in, \"\" for one "
      "given itself; ValueError for a folder without any), ready for _output_paths.");
}

}  // namespace lpir::python
