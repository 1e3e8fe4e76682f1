// The checksum record of a preview (PNG or JPEG): a PNG tEXt chunk after IHDR, or a JPEG comment
// after SOI (and JFIF's APP0), holding "kiln/checksum" and the CRC-32 of every other byte of the
// file. JPEG has no checksum of its own and a flipped byte in its scan decodes without complaint,
// so `kiln batch --resume` checks this record. Inside io/exr, beside the preview writer.
#pragma once

#include <string>
#include <vector>

namespace kiln {

// encoded ("png" or "jpeg", as preview_format names them) with the record added.
std::vector<unsigned char> with_checksum_record(const std::vector<unsigned char>& encoded,
                                                const std::string& format);

// "" when bytes hold a record whose checksum matches the rest of them, else why not, in a few words.
std::string checksum_record_problem(const std::vector<unsigned char>& bytes, const std::string& format);

// "" when path is a preview with an intact record that preview_complete finds complete at width x
// height, else why not, in a few words (the resume check of a job's --preview).
std::string preview_file_problem(const std::string& path, int width, int height);

}  // namespace kiln
