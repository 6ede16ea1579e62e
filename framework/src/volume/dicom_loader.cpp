// voxlab: loadDicom — a DICOM CT/MR series (one slice per file) read through
// GDCM (Debian's libgdcm-dev). voxlab parses no DICOM itself: gdcm::Reader
// reads each file's attributes, gdcm::StringFilter turns them into text, and
// gdcm::ImageReader decodes the pixel data (raw, RLE, the JPEG family).
// Tags are cited as (group,element) with their names from PS3.6.
//
// Which files. A folder holds the series; every regular file in it (not
// hidden, not in sub-folders) is read up to (7FE0,0010) Pixel Data. Files GDCM
// cannot read and that have no File Meta Information are not DICOM and are
// skipped; DICOM objects without pixels (DICOMDIR, reports) are skipped too.
// Images are grouped by (0020,000E) Series Instance UID: more than one group
// is an error that says to pass one file of the wanted series. Given a file,
// the series is that file's UID among the files of its folder.
//
// Geometry (PS3.3 C.7.6.2.1.1). (0020,0037) Image Orientation (Patient) holds
// the row cosine r (the direction in which the column index grows) and the
// column cosine c (the row index); the slice normal is n = r x c.
// (0020,0032) Image Position (Patient) is the centre of the first voxel; a
// slice's place in the series is its position projected on n, never its file
// name or (0020,0013) Instance Number, which scanners and exporters get wrong.
// The slice spacing comes from those projections (not (0018,0050) Slice
// Thickness nor (0018,0088) Spacing Between Slices, which need not agree):
// each gap must be within 1% of the series' typical gap (the lower median),
// else the series is incomplete (a missing slice) or uneven. (0028,0030) Pixel
// Spacing is [row spacing, column spacing], i.e. [y, x].
//
// Voxel layout. voxlab's x = DICOM columns (along r), y = rows (along c),
// z = slices in increasing position along n: a right-handed grid in patient
// space, whatever order the files came in. An oblique series (r, c not along
// the patient axes) is loaded on its own axes, since voxlab's grids are
// axis-aligned; so is a sheared one (CT gantry tilt: positions that drift
// sideways along the series). Both are said in the metadata (`voxlab info`).
//
// Values (PS3.3 C.7.6.3.1, C.11.1.1.2). Stored values are (0028,0100) Bits
// Allocated 8 or 16 bits, unsigned or two's complement by (0028,0103) Pixel
// Representation; GDCM masks the bits above (0028,0101) Bits Stored. The
// modality value is (0028,1053) Rescale Slope x stored + (0028,1052) Rescale
// Intercept, Hounsfield units for CT; slope and intercept may differ between
// slices and are applied per slice. The result is int16 when every rescaled
// value is an integer in int16's range, else float32; without a rescale
// (none, or slope 1 and intercept 0 everywhere) 8-bit data stays uint8 and
// 16-bit data uint16 or int16.
//
// Safety. Every problem is a one-line voxlab::Error "<path>: <problem>"
// naming the file and tag; GDCM's own exceptions and messages are caught and
// silenced (gdcm::Trace). Sizes are checked against the volume cap before
// the voxels are allocated, and each slice's decoded length is checked
// against Rows x Columns before GDCM writes it; an uncompressed Pixel Data
// shorter than that is an error (GDCM would fill it with zeros). GDCM's
// assert()s, live in Debian's build, can still abort on a damaged file:
// loadDicom runs this loader in a child process (dicom_child.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmReader.h>
#include <gdcmStringFilter.h>
#include <gdcmTrace.h>
#include <gdcmTransferSyntax.h>
#include <gdcmUIDs.h>

#include "dicom_internal.h"
#include "volume_io_util.h"

namespace voxlab {

namespace {

namespace fs = std::filesystem;
using detail::fail;

// ---- tags --------------------------------------------------------------------

struct TagInfo {
    gdcm::Tag tag;
    const char* name;
};

const TagInfo kTransferSyntax{{0x0002, 0x0010}, "Transfer Syntax UID"};
const TagInfo kMediaStorageSopClass{{0x0002, 0x0002}, "Media Storage SOP Class UID"};
const TagInfo kModality{{0x0008, 0x0060}, "Modality"};
const TagInfo kSeriesDescription{{0x0008, 0x103E}, "Series Description"};
const TagInfo kSeriesInstanceUid{{0x0020, 0x000E}, "Series Instance UID"};
const TagInfo kImagePosition{{0x0020, 0x0032}, "Image Position (Patient)"};
const TagInfo kImageOrientation{{0x0020, 0x0037}, "Image Orientation (Patient)"};
const TagInfo kSamplesPerPixel{{0x0028, 0x0002}, "Samples per Pixel"};
const TagInfo kNumberOfFrames{{0x0028, 0x0008}, "Number of Frames"};
const TagInfo kRows{{0x0028, 0x0010}, "Rows"};
const TagInfo kColumns{{0x0028, 0x0011}, "Columns"};
const TagInfo kPixelSpacing{{0x0028, 0x0030}, "Pixel Spacing"};
const TagInfo kBitsAllocated{{0x0028, 0x0100}, "Bits Allocated"};
const TagInfo kPixelRepresentation{{0x0028, 0x0103}, "Pixel Representation"};
const TagInfo kRescaleIntercept{{0x0028, 0x1052}, "Rescale Intercept"};
const TagInfo kRescaleSlope{{0x0028, 0x1053}, "Rescale Slope"};
const TagInfo kRescaleType{{0x0028, 0x1054}, "Rescale Type"};
const TagInfo kPixelData{{0x7FE0, 0x0010}, "Pixel Data"};

// The data set's attributes read into text (the pixel data's presence only).
const TagInfo* const kReadTags[] = {
    &kModality,       &kSeriesDescription, &kSeriesInstanceUid, &kImagePosition,
    &kImageOrientation, &kSamplesPerPixel, &kNumberOfFrames,    &kRows,
    &kColumns,        &kPixelSpacing,      &kBitsAllocated,     &kPixelRepresentation,
    &kRescaleIntercept, &kRescaleSlope,    &kRescaleType};

// "(0028,0030) Pixel Spacing"
std::string label(const TagInfo& t) {
    char code[16];
    std::snprintf(code, sizeof code, "(%04X,%04X)", unsigned(t.tag.GetGroup()),
                  unsigned(t.tag.GetElement()));
    return std::string(code) + " " + t.name;
}

// "1.2.840.10008.1.2.4.100 (MPEG2 Main Profile / Main Level)", or "(unknown)".
std::string syntaxLabel(const std::string& uid) {
    gdcm::UIDs uids;
    const char* name = uids.SetFromUID(uid.c_str()) ? uids.GetName() : nullptr;
    return "'" + uid + "' (" + (name && *name ? name : "unknown to GDCM") + ")";
}

// Text fit for a one-line message: at most 64 bytes, control characters
// and bytes that are not UTF-8 as '?' (DICOM text may be Latin-1 or worse).
std::string printable(const std::string& text) {
    std::string out;
    std::size_t i = 0;
    while (i < text.size() && out.size() < 64) {
        const auto c = static_cast<unsigned char>(text[i]);
        const std::size_t n = c < 0x80 ? 1
                            : (c & 0xE0) == 0xC0 ? 2
                            : (c & 0xF0) == 0xE0 ? 3
                            : (c & 0xF8) == 0xF0 ? 4 : 0;
        bool valid = n > 0 && i + n <= text.size() && (n > 1 || (c >= 0x20 && c != 0x7f));
        for (std::size_t k = 1; valid && k < n; ++k) valid = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
        out += valid ? text.substr(i, n) : "?";
        i += valid ? n : 1;
    }
    return i < text.size() ? out + "..." : out;
}

// ---- pass 1: each file's attributes ----------------------------------------------

enum class FileKind { NotDicom, Unreadable, NotImage, Image };

struct FileHeader {
    std::string path;
    FileKind kind = FileKind::NotDicom;
    std::string syntax;                       // (0002,0010), trimmed
    std::map<gdcm::Tag, std::string> values;  // present attributes, as text
    bool hasPixelData = false;
    // Bytes of the file after the start of the Pixel Data's value, for
    // uncompressed syntaxes (GDCM zero-fills a truncated value), else -1.
    long long pixelBytesInFile = -1;

    std::string name() const { return fs::path(path).filename().string(); }
    const std::string* find(const TagInfo& t) const {
        auto it = values.find(t.tag);
        return it == values.end() ? nullptr : &it->second;
    }
    std::string text(const TagInfo& t) const {
        const std::string* v = find(t);
        return v ? detail::trim(*v) : std::string();
    }
};

// UIDs may be padded with NUL, text with spaces (PS3.5 6.2).
std::string trimValue(std::string v) {
    while (!v.empty() && (v.back() == '\0' || v.back() == ' ')) v.pop_back();
    return detail::trim(v);
}

void silenceGdcm() {
    static const bool done = [] {
        gdcm::Trace::SetDebug(false);
        gdcm::Trace::SetWarning(false);
        gdcm::Trace::SetError(false);
        return true;
    }();
    (void)done;
}

FileHeader readHeader(const std::string& path) {
    detail::dicomReading(path);
    FileHeader h;
    h.path = path;
    gdcm::Reader reader;
    reader.SetFileName(path.c_str());
    bool ok = false;
    try {
        // Up to the Pixel Data's value, which is left unread: the stream then
        // stands at its start (no Pixel Data: at the end, position -1).
        ok = reader.ReadUpToTag(kPixelData.tag, {kPixelData.tag});
        gdcm::StringFilter filter;
        filter.SetFile(reader.GetFile());
        const gdcm::FileMetaInformation& meta = reader.GetFile().GetHeader();
        if (meta.FindDataElement(kTransferSyntax.tag))
            h.syntax = trimValue(filter.ToString(kTransferSyntax.tag));
        if (!ok) {
            h.kind = h.syntax.empty() ? FileKind::NotDicom : FileKind::Unreadable;
            return h;
        }
        const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
        for (const TagInfo* t : kReadTags)
            if (ds.FindDataElement(t->tag)) h.values[t->tag] = trimValue(filter.ToString(t->tag));
        const std::size_t at = reader.GetStreamCurrentPosition();
        h.hasPixelData = at != std::size_t(-1);
        const gdcm::TransferSyntax ts = meta.GetDataSetTransferSyntax();
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(path, ec);
        if (h.hasPixelData && !ec && size >= at && !ts.IsEncapsulated() &&
            ts != gdcm::TransferSyntax::DeflatedExplicitVRLittleEndian)
            h.pixelBytesInFile = static_cast<long long>(size - at);
        const bool directory = meta.FindDataElement(kMediaStorageSopClass.tag) &&
                               trimValue(filter.ToString(kMediaStorageSopClass.tag)) ==
                                   "1.2.840.10008.1.3.10";  // Media Storage Directory (DICOMDIR)
        const bool image = h.hasPixelData || h.find(kRows) || h.find(kColumns);
        h.kind = !directory && image ? FileKind::Image : FileKind::NotImage;
    } catch (const std::exception&) {
        h.kind = ok || !h.syntax.empty() ? FileKind::Unreadable : FileKind::NotDicom;
    }
    return h;
}

// The regular, non-hidden files of a folder, by name.
std::vector<std::string> folderFiles(const std::string& errorPath, const fs::path& folder) {
    std::vector<std::string> files;
    std::error_code ec;
    fs::directory_iterator it(folder, ec), end;
    if (ec) fail(errorPath, "cannot list the folder (" + ec.message() + ")");
    for (; it != end; it.increment(ec)) {
        if (ec) fail(errorPath, "cannot list the folder (" + ec.message() + ")");
        const std::string name = it->path().filename().string();
        std::error_code fileEc;
        if (name.empty() || name[0] == '.' || !it->is_regular_file(fileEc)) continue;
        files.push_back(it->path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::uint64_t largestFile(const std::vector<std::string>& files) {
    std::uint64_t largest = 0;
    for (const std::string& f : files) {
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(f, ec);
        if (!ec) largest = std::max<std::uint64_t>(largest, size);
    }
    return largest;
}

[[noreturn]] void failUnreadable(const std::string& path, const FileHeader& h) {
    const gdcm::TransferSyntax::TSType ts = gdcm::TransferSyntax::GetTSType(h.syntax.c_str());
    const std::string where = h.path == path ? "" : h.name() + ": ";
    if (ts == gdcm::TransferSyntax::TS_END)
        fail(path, where + "transfer syntax " + syntaxLabel(printable(h.syntax)) +
                       " cannot be read by GDCM");
    fail(path, where + "GDCM cannot read this DICOM file (transfer syntax " +
                   syntaxLabel(printable(h.syntax)) + "; damaged or truncated?)");
}

// ---- choosing the series -------------------------------------------------------

struct Scan {
    std::vector<FileHeader> images;  // the chosen series
    int notDicom = 0, notImages = 0, unreadable = 0, otherSeries = 0;
};

// "2 series: 'AX T1' (40 files, e.g. IM0001), 'SAG' (2 files, e.g. SE2_000)"
std::string seriesList(const std::map<std::string, std::vector<const FileHeader*>>& groups) {
    std::string out;
    int shown = 0;
    for (const auto& [uid, files] : groups) {
        if (++shown > 4) {
            out += ", ...";
            break;
        }
        const std::string desc = files.front()->text(kSeriesDescription);
        out += std::string(out.empty() ? "" : ", ") + "'" +
               printable(desc.empty() ? "UID " + uid : desc) + "' (" + std::to_string(files.size()) +
               (files.size() == 1 ? " file" : " files") + ", e.g. " + printable(files.front()->name()) +
               ")";
    }
    return out;
}

Scan chooseSeries(const std::string& path, bool isFolder) {
    const fs::path folder = isFolder ? fs::path(path) : fs::path(path).parent_path();
    std::vector<FileHeader> headers;
    if (!isFolder) {
        headers.push_back(readHeader(path));
        if (headers[0].kind == FileKind::NotDicom) fail(path, "not a DICOM file (GDCM cannot read it)");
        if (headers[0].kind == FileKind::Unreadable) failUnreadable(path, headers[0]);
        if (headers[0].kind == FileKind::NotImage)
            fail(path, "a DICOM file without an image (no Rows, Columns or Pixel Data)");
    }
    const std::string chosenUid = isFolder ? "" : headers[0].text(kSeriesInstanceUid);
    const std::vector<std::string> files = folderFiles(path, folder.empty() ? fs::path(".") : folder);
    detail::dicomMemoryBudget(2 * largestFile(files));  // an attribute holds at most its file
    for (const std::string& file : files) {
        if (!isFolder && fs::path(file).filename() == fs::path(path).filename()) continue;
        headers.push_back(readHeader(file));
    }
    Scan scan;
    std::map<std::string, std::vector<const FileHeader*>> groups;
    for (const FileHeader& h : headers) {
        if (h.kind == FileKind::NotDicom) ++scan.notDicom;
        if (h.kind == FileKind::NotImage) ++scan.notImages;
        if (h.kind == FileKind::Unreadable) {
            if (isFolder) failUnreadable(path, h);
            ++scan.unreadable;  // a sibling of the given file: its series is unknown
        }
        if (h.kind == FileKind::Image) groups[h.text(kSeriesInstanceUid)].push_back(&h);
    }
    if (groups.empty()) {
        fail(path, "no DICOM image files in this folder (" + std::to_string(headers.size()) +
                       " files: " + std::to_string(scan.notDicom) + " not DICOM, " +
                       std::to_string(scan.notImages) + " DICOM without an image)");
    }
    if (isFolder && groups.size() > 1) {
        fail(path, "the folder holds " + std::to_string(groups.size()) + " series: " + seriesList(groups) +
                       "; pass one file of the wanted series instead of the folder");
    }
    const auto& chosen = isFolder ? groups.begin()->second : groups[chosenUid];
    for (const auto& [uid, files] : groups)
        if (&files != &chosen) scan.otherSeries += int(files.size());
    for (const FileHeader* h : chosen) scan.images.push_back(*h);
    return scan;
}

// ---- the slices' geometry --------------------------------------------------------

struct Slice {
    std::string path, name;
    int rows = 0, cols = 0, bitsAllocated = 0, pixelRepresentation = 0;
    glm::dvec3 position{0.0}, rowCosine{0.0}, colCosine{0.0};
    glm::dvec2 pixelSpacing{0.0};  // as in (0028,0030): [row spacing (y), column spacing (x)]
    double slope = 1.0, intercept = 0.0;
    bool rescaled = false;  // the file has a slope or an intercept
    double along = 0.0;     // position . normal
};

// The numbers of a multi-valued decimal (DS) or integer (IS/US) attribute.
std::vector<double> numbers(const std::string& path, const FileHeader& h, const TagInfo& t,
                            std::size_t count, bool required) {
    const std::string* raw = h.find(t);
    if (!raw || raw->empty()) {
        if (!required) return {};
        fail(path, h.name() + ": missing " + label(t));
    }
    std::vector<double> out;
    std::size_t start = 0;
    while (start <= raw->size()) {
        std::size_t end = raw->find('\\', start);
        if (end == std::string::npos) end = raw->size();
        double v = 0.0;
        if (!detail::parseDouble(detail::trim(raw->substr(start, end - start)), v) || !std::isfinite(v))
            fail(path, h.name() + ": " + label(t) + " is not a number: '" + printable(*raw) + "'");
        out.push_back(v);
        start = end + 1;
    }
    if (out.size() != count) {
        fail(path, h.name() + ": " + label(t) + " has " + std::to_string(out.size()) + " values, expected " +
                       std::to_string(count) + ": '" + printable(*raw) + "'");
    }
    return out;
}

int whole(const std::string& path, const FileHeader& h, const TagInfo& t, int lo, int hi, int fallback,
          bool required) {
    const std::vector<double> v = numbers(path, h, t, 1, required);
    if (v.empty()) return fallback;
    if (v[0] != std::floor(v[0]) || v[0] < lo || v[0] > hi) {
        fail(path, h.name() + ": " + label(t) + " is " + printable(h.text(t)) + ", expected " +
                       std::to_string(lo) + ".." + std::to_string(hi));
    }
    return int(v[0]);
}

void readOrientation(const std::string& path, const FileHeader& h, Slice& s) {
    const std::vector<double> o = numbers(path, h, kImageOrientation, 6, true);
    glm::dvec3 r(o[0], o[1], o[2]), c(o[3], o[4], o[5]);
    const double lr = glm::length(r), lc = glm::length(c);
    if (std::abs(lr - 1.0) > 1e-3 || std::abs(lc - 1.0) > 1e-3 || std::abs(glm::dot(r, c)) > 1e-3) {
        fail(path, h.name() + ": " + label(kImageOrientation) + " '" + printable(h.text(kImageOrientation)) +
                       "' is not two orthogonal unit vectors");
    }
    s.rowCosine = r / lr;
    s.colCosine = c / lc;
}

Slice readSlice(const std::string& path, const FileHeader& h) {
    Slice s;
    s.path = h.path;
    s.name = h.name();
    if (!h.hasPixelData) fail(path, h.name() + ": missing " + label(kPixelData));
    s.rows = whole(path, h, kRows, 1, 65535, 0, true);
    s.cols = whole(path, h, kColumns, 1, 65535, 0, true);
    s.bitsAllocated = whole(path, h, kBitsAllocated, 1, 64, 0, true);
    s.pixelRepresentation = whole(path, h, kPixelRepresentation, 0, 1, 0, true);
    const int samples = whole(path, h, kSamplesPerPixel, 1, 4, 1, false);
    const int frames = whole(path, h, kNumberOfFrames, 1, 1 << 30, 1, false);
    if (samples != 1)
        fail(path, h.name() + ": " + std::to_string(samples) + " samples per pixel (colour); voxlab reads " +
                       "grey-level series only");
    if (frames != 1)
        fail(path, h.name() + ": a multi-frame image (" + std::to_string(frames) + " frames); voxlab reads " +
                       "series of one slice per file");
    if (s.bitsAllocated != 8 && s.bitsAllocated != 16)
        fail(path, h.name() + ": " + label(kBitsAllocated) + " is " + std::to_string(s.bitsAllocated) +
                       "; voxlab reads 8- and 16-bit data");
    const long long expected = (long long)s.rows * s.cols * (s.bitsAllocated / 8);
    if (h.pixelBytesInFile >= 0 && h.pixelBytesInFile < expected)
        fail(path, h.name() + ": truncated " + label(kPixelData) + ": " + std::to_string(h.pixelBytesInFile) +
                       " bytes, expected " + std::to_string(expected));
    const std::vector<double> p = numbers(path, h, kImagePosition, 3, true);
    s.position = glm::dvec3(p[0], p[1], p[2]);
    readOrientation(path, h, s);
    const std::vector<double> ps = numbers(path, h, kPixelSpacing, 2, true);
    if (!(ps[0] > 0.0 && ps[1] > 0.0))
        fail(path, h.name() + ": " + label(kPixelSpacing) + " must be positive, got '" +
                       printable(h.text(kPixelSpacing)) + "'");
    s.pixelSpacing = glm::dvec2(ps[0], ps[1]);
    const std::vector<double> slope = numbers(path, h, kRescaleSlope, 1, false);
    const std::vector<double> intercept = numbers(path, h, kRescaleIntercept, 1, false);
    if (!slope.empty()) s.slope = slope[0];
    if (!intercept.empty()) s.intercept = intercept[0];
    s.rescaled = !slope.empty() || !intercept.empty();
    if (s.slope == 0.0) fail(path, h.name() + ": " + label(kRescaleSlope) + " is 0");
    return s;
}

// The slice most others look like (size, pixel format, orientation and
// spacing to 3 decimals), so that an error names the odd one out.
const Slice& typicalSlice(const std::vector<Slice>& slices, int& alike) {
    std::map<std::string, std::pair<int, const Slice*>> kinds;
    for (const Slice& s : slices) {
        char key[256];
        std::snprintf(key, sizeof key, "%d %d %d %d %.3f %.3f %.3f %.3f %.3f %.3f %.3g %.3g", s.cols, s.rows,
                      s.bitsAllocated, s.pixelRepresentation, s.rowCosine.x, s.rowCosine.y, s.rowCosine.z,
                      s.colCosine.x, s.colCosine.y, s.colCosine.z, s.pixelSpacing.x, s.pixelSpacing.y);
        auto& kind = kinds[key];
        if (kind.first++ == 0) kind.second = &s;
    }
    auto best = kinds.begin();
    for (auto it = kinds.begin(); it != kinds.end(); ++it)
        if (it->second.first > best->second.first) best = it;
    alike = best->second.first;
    return *best->second.second;
}

// Every slice must match the typical one in size, pixel format, orientation
// and pixel spacing: else the folder mixes acquisitions under one UID.
void checkSameKind(const std::string& path, const std::vector<Slice>& slices) {
    int alike = 0;
    const Slice& a = typicalSlice(slices, alike);
    auto mixed = [&](const Slice& b, const std::string& what) {
        fail(path, "mixed series: " + b.name + " " + what + " (like " + a.name + ": " + std::to_string(alike) +
                       " of " + std::to_string(slices.size()) + " slices)");
    };
    for (const Slice& b : slices) {
        if (b.cols != a.cols || b.rows != a.rows)
            mixed(b, "is " + std::to_string(b.cols) + "x" + std::to_string(b.rows) + " (Columns x Rows), not " +
                         std::to_string(a.cols) + "x" + std::to_string(a.rows));
        if (b.bitsAllocated != a.bitsAllocated)
            mixed(b, "has " + std::to_string(b.bitsAllocated) + " bits allocated, not " +
                         std::to_string(a.bitsAllocated));
        if (b.pixelRepresentation != a.pixelRepresentation)
            mixed(b, std::string("is ") + (b.pixelRepresentation ? "signed" : "unsigned") + ", not " +
                         (a.pixelRepresentation ? "signed" : "unsigned") + " (" + label(kPixelRepresentation) + ")");
        const double dr = glm::length(b.rowCosine - a.rowCosine), dc = glm::length(b.colCosine - a.colCosine);
        if (dr > 1e-3 || dc > 1e-3) mixed(b, "has another " + label(kImageOrientation));
        const glm::dvec2 dp = glm::abs(b.pixelSpacing - a.pixelSpacing);
        if (dp.x > 1e-3 * a.pixelSpacing.x || dp.y > 1e-3 * a.pixelSpacing.y)
            mixed(b, "has another " + label(kPixelSpacing));
    }
}

std::string mm(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

// Sorts the slices along the normal and returns the slice spacing: the mean
// gap, once every gap is within 1% of the typical (lower median) gap.
double sortAndSpace(const std::string& path, std::vector<Slice>& slices, const Scan& scan) {
    const glm::dvec3 n = glm::normalize(glm::cross(slices[0].rowCosine, slices[0].colCosine));
    for (Slice& s : slices) s.along = glm::dot(s.position, n);
    std::sort(slices.begin(), slices.end(), [](const Slice& a, const Slice& b) { return a.along < b.along; });
    std::vector<double> gaps;
    for (std::size_t k = 1; k < slices.size(); ++k) gaps.push_back(slices[k].along - slices[k - 1].along);
    std::vector<double> sorted = gaps;
    std::sort(sorted.begin(), sorted.end());
    const double typical = sorted[(sorted.size() - 1) / 2];
    const double extent = slices.back().along - slices.front().along;
    for (std::size_t k = 0; k < gaps.size(); ++k) {
        const Slice &a = slices[k], &b = slices[k + 1];
        const std::string between = a.name + " and " + b.name + " (at " + mm(a.along) + " and " + mm(b.along) +
                                    " mm along the normal)";
        if (gaps[k] <= 1e-3 * std::max(typical, extent / double(gaps.size())))
            fail(path, "mixed series: two slices at the same position, " + between);
        const double tolerance = std::max(0.01 * typical, 1e-6);
        if (std::abs(gaps[k] - typical) <= tolerance) continue;
        // A whole number of spacings: slices are missing.
        const long steps = std::lround(gaps[k] / typical);
        if (steps >= 2 && std::abs(gaps[k] - double(steps) * typical) <= double(steps) * tolerance) {
            std::string skipped;
            if (scan.notDicom + scan.unreadable > 0)
                skipped = "; " + std::to_string(scan.notDicom + scan.unreadable) + " unreadable files were skipped";
            fail(path, "incomplete series: a gap of " + mm(gaps[k]) + " mm between " + between +
                           " where the slices are " + mm(typical) + " mm apart (" + std::to_string(steps - 1) +
                           " missing slice" + (steps > 2 ? "s)" : ")") + skipped);
        }
        fail(path, "uneven slice spacing: " + mm(gaps[k]) + " mm between " + between + " where the slices are " +
                       mm(typical) + " mm apart");
    }
    return extent / double(gaps.size());
}

// ---- metadata --------------------------------------------------------------------

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

// "L", "P", "S" ... for a direction along a patient axis (DICOM's LPS), else
// the vector.
std::string direction(glm::dvec3 v) {
    static const char* names[3][2] = {{"L", "R"}, {"P", "A"}, {"S", "I"}};
    for (int a = 0; a < 3; ++a)
        if (std::abs(v[a]) > 0.9999) return names[a][v[a] > 0 ? 0 : 1];
    char text[64];
    std::snprintf(text, sizeof text, "(%.3f %.3f %.3f)", v.x, v.y, v.z);
    return text;
}

std::string orientationText(const Slice& first, const Slice& last) {
    const glm::dvec3 r = first.rowCosine, c = first.colCosine, n = glm::normalize(glm::cross(r, c));
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(n[a]) > std::abs(n[axis])) axis = a;
    static const char* planes[3] = {"sagittal", "coronal", "axial"};
    const bool oblique = !(std::abs(n[axis]) > 0.9999);  // 0.8 degrees
    const double off = std::acos(std::min(1.0, std::abs(n[axis]))) * kDegrees;
    std::string out = oblique ? "oblique (" + mm(off) + " deg from " + planes[axis] + ")" : planes[axis];
    out += ": +x = " + direction(r) + ", +y = " + direction(c) + ", +z = " + direction(n) + " (patient LPS)";
    const glm::dvec3 d = last.position - first.position;
    const double sideways = glm::length(d - glm::dot(d, n) * n);
    const bool sheared = sideways > 0.01 * std::min(first.pixelSpacing.x, first.pixelSpacing.y);
    if (sheared) {
        const double tilt = std::atan2(sideways, std::abs(glm::dot(d, n))) * kDegrees;
        out += "; sheared: the slices drift " + mm(sideways) + " mm sideways (gantry tilt " + mm(tilt) + " deg)";
    }
    if (oblique || sheared) out += "; loaded on the image's own axes, not resampled";
    return out;
}

std::string rescaleText(const std::vector<Slice>& slices, const FileHeader& first, VoxelType type) {
    bool same = true, any = false;
    for (const Slice& s : slices) {
        same = same && s.slope == slices[0].slope && s.intercept == slices[0].intercept;
        any = any || s.rescaled;
    }
    // (0028,1054) Rescale Type: "HU", "US" (unspecified), ...; CT is in HU by definition.
    std::string units = printable(first.text(kRescaleType));
    if (units.empty() && first.text(kModality) == "CT") units = "HU";
    units = units == "US" ? " (Rescale Type US: unspecified units)" : units.empty() ? "" : " in " + units;
    const std::string as = std::string(", as ") + voxelTypeName(type);
    if (!any) return "none (no Rescale Slope/Intercept): stored values" + as;
    if (!same) return "value = slope x stored + intercept, per slice (they differ)" + units + as;
    const double m = slices[0].slope, b = slices[0].intercept;
    if (m == 1.0 && b == 0.0) return "slope 1, intercept 0: stored values" + as;
    return "value = " + mm(m) + " x stored " + (b < 0 ? "- " : "+ ") + mm(std::abs(b)) + units + as;
}

// ---- pass 2: pixels --------------------------------------------------------------

// Decodes one slice into `out` (rows x cols values of `format`, host order).
void readPixels(const std::string& path, const Slice& s, gdcm::PixelFormat::ScalarType format, std::uint8_t* out,
                std::size_t bytes) {
    detail::dicomReading(s.path);
    gdcm::ImageReader reader;
    reader.SetFileName(s.path.c_str());
    bool ok = false;
    try {
        ok = reader.Read();
    } catch (const std::exception&) {
        ok = false;
    }
    if (!ok) fail(path, s.name + ": GDCM cannot read the image (damaged, or changed while loading?)");
    const gdcm::Image& image = reader.GetImage();
    gdcm::StringFilter filter;
    filter.SetFile(reader.GetFile());
    const std::string uid = trimValue(filter.ToString(kTransferSyntax.tag));
    const unsigned* dims = image.GetDimensions();
    if (image.GetNumberOfDimensions() < 2 || dims[0] != unsigned(s.cols) || dims[1] != unsigned(s.rows) ||
        (image.GetNumberOfDimensions() > 2 && dims[2] != 1))
        fail(path, s.name + ": GDCM reads an image of another size than its Rows and Columns");
    if (image.GetPixelFormat().GetScalarType() != format || image.GetPixelFormat().GetSamplesPerPixel() != 1)
        fail(path, "mixed series: " + s.name + " has another pixel format than the first slice");
    if (image.GetBufferLength() != bytes)
        fail(path, s.name + ": its pixel data decodes to " + std::to_string(image.GetBufferLength()) +
                       " bytes, expected " + std::to_string(bytes));
    bool decoded = false;
    try {
        decoded = image.GetBuffer(reinterpret_cast<char*>(out));
    } catch (const std::exception&) {
        decoded = false;
    }
    if (!decoded) {
        if (image.GetTransferSyntax().IsEncapsulated())
            fail(path, s.name + ": GDCM cannot decode the compressed transfer syntax " + syntaxLabel(printable(uid)));
        fail(path, s.name + ": GDCM cannot decode the pixel data (transfer syntax " + syntaxLabel(printable(uid)) +
                       "; truncated?)");
    }
}

// ---- values: stored -> volume type -------------------------------------------------

template <typename T>
T storedAt(const std::vector<std::uint8_t>& raw, std::size_t i) {
    T v;
    std::memcpy(&v, raw.data() + i * sizeof(T), sizeof(T));
    return v;
}

double storedValue(const std::vector<std::uint8_t>& raw, gdcm::PixelFormat::ScalarType f, std::size_t i) {
    switch (f) {
        case gdcm::PixelFormat::UINT8: return raw[i];
        case gdcm::PixelFormat::INT8: return static_cast<std::int8_t>(raw[i]);
        case gdcm::PixelFormat::UINT16: return storedAt<std::uint16_t>(raw, i);
        default: return storedAt<std::int16_t>(raw, i);
    }
}

// The stored slices as the volume's voxels: rescaled per slice, in the
// narrowest type that holds every value exactly (see the top of the file).
std::vector<std::uint8_t> toVolumeValues(const std::string& path, std::vector<std::uint8_t> raw,
                                         gdcm::PixelFormat::ScalarType f, const std::vector<Slice>& slices,
                                         glm::ivec3 dims, VoxelType& type) {
    const std::size_t perSlice = std::size_t(dims.x) * std::size_t(dims.y), n = perSlice * slices.size();
    bool identity = true;
    for (const Slice& s : slices) identity = identity && s.slope == 1.0 && s.intercept == 0.0;
    if (identity && f != gdcm::PixelFormat::INT8) {
        type = f == gdcm::PixelFormat::UINT8 ? VoxelType::UInt8
             : f == gdcm::PixelFormat::UINT16 ? VoxelType::UInt16 : VoxelType::Int16;
        return raw;
    }
    bool integral = true;
    for (std::size_t i = 0; i < n && integral; ++i) {
        const Slice& s = slices[i / perSlice];
        const double v = s.slope * storedValue(raw, f, i) + s.intercept;
        integral = v == std::floor(v) && v >= -32768.0 && v <= 32767.0;
    }
    type = integral ? VoxelType::Int16 : VoxelType::Float32;
    detail::checkedVolumeBytes(path, "series", dims.x, dims.y, dims.z, type);
    std::vector<std::uint8_t> out(n * voxelTypeSize(type));
    for (std::size_t i = 0; i < n; ++i) {
        const Slice& s = slices[i / perSlice];
        const double v = s.slope * storedValue(raw, f, i) + s.intercept;
        if (integral) {
            const auto w = static_cast<std::int16_t>(v);
            std::memcpy(out.data() + 2 * i, &w, 2);
        } else {
            const auto w = static_cast<float>(v);
            if (!std::isfinite(w)) fail(path, slices[i / perSlice].name + ": a rescaled value overflows float32");
            std::memcpy(out.data() + 4 * i, &w, 4);
        }
    }
    return out;
}

gdcm::PixelFormat::ScalarType storedFormat(const Slice& s) {
    if (s.bitsAllocated == 8) return s.pixelRepresentation ? gdcm::PixelFormat::INT8 : gdcm::PixelFormat::UINT8;
    return s.pixelRepresentation ? gdcm::PixelFormat::INT16 : gdcm::PixelFormat::UINT16;
}

// The volume's name: the folder's ("series/" -> "series").
std::string seriesName(const std::string& path, bool isFolder) {
    fs::path p = fs::path(path);
    if (!isFolder) p = p.parent_path();
    if (!p.has_filename()) p = p.parent_path();  // a trailing '/'
    const std::string name = p.filename().string();
    return name.empty() || name == "." ? fs::absolute(p).filename().string() : name;
}

Volume buildSeriesVolume(const std::string& path, bool isFolder, glm::ivec3 dims, VoxelType type,
                         glm::dvec3 spacing, std::vector<std::uint8_t> voxels) {
    try {
        return Volume(dims, type, spacing, std::move(voxels), seriesName(path, isFolder));
    } catch (const detail::VolumeError& e) {
        fail(path, e.problem());
    }
}

}  // namespace

Volume detail::loadDicomHere(const std::string& path) {
    silenceGdcm();
    if (path.empty()) throw Error("(empty path): no such file");
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) fail(path, "no such file or folder");
    const bool isFolder = fs::is_directory(st);
    if (!isFolder) detail::fileSize(path);  // "cannot open file for reading", ...

    const Scan scan = chooseSeries(path, isFolder);
    if (scan.images.size() < 2) {
        fail(path, "only one slice (" + scan.images[0].name() + ") in the series; a volume needs at least 2" +
                       (scan.otherSeries > 0 ? " (other series in the folder: " + std::to_string(scan.otherSeries) +
                                                   " files)"
                                             : ""));
    }
    std::vector<Slice> slices;
    for (const FileHeader& h : scan.images) slices.push_back(readSlice(path, h));
    checkSameKind(path, slices);
    const double dz = sortAndSpace(path, slices, scan);

    const glm::ivec3 dims(slices[0].cols, slices[0].rows, int(slices.size()));
    const gdcm::PixelFormat::ScalarType format = storedFormat(slices[0]);
    const VoxelType storedType = slices[0].bitsAllocated == 8 ? VoxelType::UInt8 : VoxelType::UInt16;
    const std::uint64_t bytes = detail::checkedVolumeBytes(path, "series", dims.x, dims.y, dims.z, storedType);
    // The stored voxels, their rescaled copy (float32 at most), and GDCM's
    // reading of a slice (its file and the decoded slice, twice).
    std::vector<std::string> files;
    for (const Slice& s : slices) files.push_back(s.path);
    const std::uint64_t sliceBytes = bytes / slices.size(), voxels = std::uint64_t(dims.x) * dims.y * dims.z;
    detail::dicomMemoryBudget(bytes + 4 * voxels + 2 * largestFile(files) + 2 * sliceBytes);
    std::vector<std::uint8_t> raw(static_cast<std::size_t>(bytes));
    for (std::size_t k = 0; k < slices.size(); ++k)
        readPixels(path, slices[k], format, raw.data() + k * sliceBytes, sliceBytes);

    VoxelType type = storedType;
    std::vector<std::uint8_t> values = toVolumeValues(path, std::move(raw), format, slices, dims, type);
    const glm::dvec3 spacing(slices[0].pixelSpacing[1], slices[0].pixelSpacing[0], dz);
    Volume volume = buildSeriesVolume(path, isFolder, dims, type, spacing, std::move(values));
    const FileHeader& first = scan.images.front();
    const std::string description = first.text(kSeriesDescription);
    volume.setMetadata({
        {"series", description.empty() ? "(no Series Description)" : printable(description)},
        {"modality", first.text(kModality).empty() ? "(none)" : printable(first.text(kModality))},
        {"slices", std::to_string(slices.size()) + " files, ordered by Image Position (Patient) along the normal, " +
                       mm(dz) + " mm apart"},
        {"orientation", orientationText(slices.front(), slices.back())},
        {"rescale", rescaleText(slices, first, type)},
    });
    return volume;
}

}  // namespace voxlab
