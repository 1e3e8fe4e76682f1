#include "app/text_output.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace kiln {

void write_text_atomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".kiln-tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      out.close();
      std::remove(temporary.c_str());
      throw io_error(path, "cannot write the file");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw io_error(path, "cannot move the finished file into place");
  }
}

}  // namespace kiln
