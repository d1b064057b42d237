#include "swa/dds/security_check.h"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <cerrno>
#include <cstdio>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace swa::dds {

namespace {

template <class T, void (*Free)(T*)>
struct Freer {
  void operator()(T* p) const { Free(p); }
};
using BioPtr = std::unique_ptr<BIO, Freer<BIO, BIO_free_all>>;
using X509Ptr = std::unique_ptr<X509, Freer<X509, X509_free>>;
using KeyPtr = std::unique_ptr<EVP_PKEY, Freer<EVP_PKEY, EVP_PKEY_free>>;
using StorePtr = std::unique_ptr<X509_STORE, Freer<X509_STORE, X509_STORE_free>>;
using StoreCtxPtr = std::unique_ptr<X509_STORE_CTX, Freer<X509_STORE_CTX, X509_STORE_CTX_free>>;
using Pkcs7Ptr = std::unique_ptr<PKCS7, Freer<PKCS7, PKCS7_free>>;
struct InfoStackFreer {
  void operator()(STACK_OF(X509_INFO) * s) const { sk_X509_INFO_pop_free(s, X509_INFO_free); }
};
using InfoStackPtr = std::unique_ptr<STACK_OF(X509_INFO), InfoStackFreer>;
struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

using Problem = std::optional<std::string>;

// Credentials are a few KiB; the bound keeps a wrong path (a log, a device) from being read whole, and the size
// within OpenSSL's int lengths.
constexpr std::size_t kMaxFileBytes = std::size_t{1} << 20;

// OpenSSL's first queued error (the root cause: later entries wrap it) with its detail text; the queue is empty
// afterwards, so no error of ours is left for the next OpenSSL user of this thread to misread.
std::string opensslReason() {
  const char* data = nullptr;
  int flags = 0;
  const unsigned long code = ERR_get_error_all(nullptr, nullptr, nullptr, &data, &flags);
  std::string reason;
  if (code != 0) {
    const char* text = ERR_reason_error_string(code);
    reason = text != nullptr ? text : "OpenSSL error " + std::to_string(code);
    if (data != nullptr && (flags & ERR_TXT_STRING) != 0 && *data != '\0') reason += std::string(": ") + data;
  }
  ERR_clear_error();
  return reason.empty() ? "no reason given by OpenSSL" : reason;
}

// A key file protected by a passphrase must fail, not prompt on the terminal of a drone's service.
int noPassphrase(char*, int, int, void*) { return -1; }

// Reads all of `path` into `bytes`; why not, if it cannot.
Problem readWhole(const std::string& path, std::string& bytes) {
  std::unique_ptr<std::FILE, FileCloser> in(std::fopen(path.c_str(), "rb"));
  if (!in) return path + " cannot be opened (" + std::generic_category().message(errno) + ")";
  bytes.clear();
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, in.get())) > 0) {
    bytes.append(buffer, n);
    if (bytes.size() > kMaxFileBytes) return path + " is larger than 1 MiB: not a credential file";
  }
  if (std::ferror(in.get())) return path + " cannot be read (" + std::generic_category().message(errno) + ")";
  if (bytes.empty()) return path + " is empty";
  return std::nullopt;
}

BioPtr memoryBio(const std::string& bytes) {
  return BioPtr(BIO_new_mem_buf(bytes.data(), static_cast<int>(bytes.size())));
}

std::string bioText(BIO* mem) {
  char* data = nullptr;
  const long n = BIO_get_mem_data(mem, &data);
  return data != nullptr && n > 0 ? std::string(data, static_cast<std::size_t>(n)) : std::string();
}

// Every certificate of the CA file into `store`, as Fast DDS loads its identity and permissions CA.
Problem loadCa(const std::string& path, X509_STORE* store) {
  std::string bytes;
  if (Problem p = readWhole(path, bytes)) return p;
  const BioPtr bio = memoryBio(bytes);
  InfoStackPtr infos(bio ? PEM_X509_INFO_read_bio(bio.get(), nullptr, noPassphrase, nullptr) : nullptr);
  if (!infos) return path + " is not a PEM file (" + opensslReason() + ")";
  int added = 0;
  for (int i = 0; i < sk_X509_INFO_num(infos.get()); ++i) {
    const X509_INFO* info = sk_X509_INFO_value(infos.get(), i);
    if (info->x509 != nullptr && X509_STORE_add_cert(store, info->x509) == 1) ++added;
  }
  ERR_clear_error();
  if (added == 0) return path + " holds no PEM certificate";
  return std::nullopt;
}

// The first object of `path` that `read` (PEM_read_bio_X509, PEM_read_bio_PrivateKey) finds, into `out`.
template <class T, class Free>
Problem loadPem(const std::string& path, T* (*read)(BIO*, T**, pem_password_cb*, void*), const std::string& what,
                std::unique_ptr<T, Free>& out) {
  std::string bytes;
  if (Problem p = readWhole(path, bytes)) return p;
  const BioPtr bio = memoryBio(bytes);
  out.reset(bio ? read(bio.get(), nullptr, noPassphrase, nullptr) : nullptr);
  if (!out) return path + " holds no readable " + what + " (" + opensslReason() + ")";
  return std::nullopt;
}

// The chain check of Fast DDS's PKI-DH plugin, with its flags (not X509_V_FLAG_X509_STRICT).
Problem verifyCertificate(const SecurityFiles& f, X509_STORE* store, X509* cert) {
  StoreCtxPtr ctx(X509_STORE_CTX_new());
  if (!ctx || X509_STORE_CTX_init(ctx.get(), store, cert, nullptr) != 1) {
    return "OpenSSL cannot set up the verification of " + f.certificate + " (" + opensslReason() + ")";
  }
  X509_STORE_CTX_set_flags(ctx.get(), X509_V_FLAG_CHECK_SS_SIGNATURE | X509_V_FLAG_POLICY_CHECK);
  if (X509_verify_cert(ctx.get()) == 1) return std::nullopt;
  const int error = X509_STORE_CTX_get_error(ctx.get());
  ERR_clear_error();
  return f.certificate + " does not verify against " + f.ca + ": " + X509_verify_cert_error_string(error);
}

// The signed text of an `openssl smime -sign -text` document, verified as Fast DDS 2.9's Access-Permissions plugin
// verifies it (PKCS7_verify against the CA, text mode).
Problem verifySigned(const std::string& path, const std::string& ca, X509_STORE* store, std::string& text) {
  std::string bytes;
  if (Problem p = readWhole(path, bytes)) return p;
  const std::string fails = "signature of " + path + " does not verify against " + ca;
  const BioPtr bio = memoryBio(bytes);
  BIO* content = nullptr;
  const Pkcs7Ptr p7(bio ? SMIME_read_PKCS7(bio.get(), &content) : nullptr);
  const BioPtr content_owner(content);
  if (!p7) return fails + ": the file is not a readable S/MIME signed document (OpenSSL: " + opensslReason() + ")";
  const BioPtr out(BIO_new(BIO_s_mem()));
  if (!out) return "OpenSSL cannot allocate a buffer to verify " + path;
  if (PKCS7_verify(p7.get(), nullptr, store, content, out.get(), PKCS7_TEXT) != 1) {
    return fails + " (modified after signing, or signed by another CA; OpenSSL: " + opensslReason() + ")";
  }
  text = bioText(out.get());
  return std::nullopt;
}

// The subject as Fast DDS 2.9's PKI-DH plugin prints it for the permissions check.
std::string rfc2253Subject(X509* cert) {
  const BioPtr mem(BIO_new(BIO_s_mem()));
  if (!mem ||
      X509_NAME_print_ex(mem.get(), X509_get_subject_name(cert), 0, XN_FLAG_RFC2253 & ~ASN1_STRFLGS_ESC_MSB) < 0) {
    ERR_clear_error();
    return "";
  }
  return bioText(mem.get());
}

std::string trim(const std::string& s, const char* blanks) {
  const std::size_t first = s.find_first_not_of(blanks);
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(blanks) - first + 1);
}

// Fast DDS 2.9 compares a grant's subject with the certificate's attribute by attribute, in order, blanks around
// each ignored: "CN=a, O=b" grants "CN=a,O=b", "O=b,CN=a" does not.
bool sameSubject(const std::string& a, const std::string& b) {
  const auto split = [](const std::string& s) {
    std::vector<std::string> parts;
    std::size_t begin = 0;
    for (std::size_t comma = s.find(',');; comma = s.find(',', begin)) {
      parts.push_back(trim(s.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin), " "));
      if (comma == std::string::npos) break;
      begin = comma + 1;
    }
    return parts;
  };
  return split(a) == split(b);
}

// The XML character data as the parser hands it to Fast DDS (predefined entities only: the documents have no DTD).
std::string xmlText(const std::string& raw) {
  static const std::pair<const char*, char> kEntities[] = {
      {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}, {"&amp;", '&'}};
  std::string s = trim(raw, " \t\r\n");
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    bool replaced = false;
    for (const auto& [entity, c] : kEntities) {
      if (s.compare(i, std::char_traits<char>::length(entity), entity) == 0) {
        out += c;
        i += std::char_traits<char>::length(entity);
        replaced = true;
        break;
      }
    }
    if (!replaced) out += s[i++];
  }
  return out;
}

std::vector<std::string> grantedSubjects(const std::string& permissions_xml) {
  static const std::string kOpen = "<subject_name>", kClose = "</subject_name>";
  std::vector<std::string> subjects;
  for (std::size_t at = permissions_xml.find(kOpen); at != std::string::npos;
       at = permissions_xml.find(kOpen, at + kOpen.size())) {
    const std::size_t begin = at + kOpen.size();
    const std::size_t end = permissions_xml.find(kClose, begin);
    if (end == std::string::npos) break;
    subjects.push_back(xmlText(permissions_xml.substr(begin, end - begin)));
  }
  return subjects;
}

Problem checkAll(const SecurityFiles& f) {
  const StorePtr store(X509_STORE_new());
  if (!store) return std::string("OpenSSL cannot allocate a certificate store");
  if (Problem p = loadCa(f.ca, store.get())) return p;

  X509Ptr cert;
  if (Problem p = loadPem(f.certificate, PEM_read_bio_X509, "PEM certificate", cert)) return p;
  if (Problem p = verifyCertificate(f, store.get(), cert.get())) return p;

  KeyPtr key;
  if (Problem p = loadPem(f.private_key, PEM_read_bio_PrivateKey, "unencrypted PEM private key", key)) return p;
  if (X509_check_private_key(cert.get(), key.get()) != 1) {
    return f.private_key + " is not the private key of " + f.certificate + " (OpenSSL: " + opensslReason() + ")";
  }

  std::string text;
  if (Problem p = verifySigned(f.governance, f.ca, store.get(), text)) return p;
  if (Problem p = verifySigned(f.permissions, f.ca, store.get(), text)) return p;

  const std::string subject = rfc2253Subject(cert.get());
  const std::vector<std::string> granted = grantedSubjects(text);
  if (granted.empty()) return f.permissions + " grants no subject (no <subject_name> in its signed text)";
  for (const std::string& g : granted) {
    if (sameSubject(g, subject)) return std::nullopt;
  }
  std::string list;
  for (const std::string& g : granted) list += (list.empty() ? "'" : ", '") + g + "'";
  return f.permissions + " grants subject " + list + " but " + f.certificate + " is '" + subject + "'";
}

}  // namespace

std::optional<std::string> credentialProblem(const SecurityFiles& f) {
  ERR_clear_error();  // whatever Fast DDS left queued on this thread is not ours to report
  Problem p = checkAll(f);
  ERR_clear_error();
  return p;
}

}  // namespace swa::dds
