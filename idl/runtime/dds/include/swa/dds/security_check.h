#pragma once
// Why DDS Security would refuse a participant's credentials, in words. Fast DDS 2.9 reports a refused identity or
// permissions document only as "Cannot create participant due to initialization error"; this repeats, with OpenSSL,
// the checks its builtin plugins make on the files (PKI-DH: the identity chain and key; Access-Permissions: the
// S/MIME signatures and the granted subject) and names the first that fails. No DDS include.

#include <optional>
#include <string>

#include "swa/dds/deployment.h"

namespace swa::dds {

// The first problem with `f`, as one sentence naming the file(s) concerned; nullopt when every check passes.
// In order: each file readable and parseable when it is needed; f.certificate verifies against f.ca (OpenSSL's
// reason); f.private_key is the certificate's key; the S/MIME signatures of f.governance and f.permissions verify
// against f.ca; a grant of f.permissions names the certificate's RFC 2253 subject.
// Not checked: the grant's validity dates and the XML schema of the documents; nor the domains they cover, which
// Fast DDS 2.9.1 does not refuse at participant creation (its endpoints fail later).
std::optional<std::string> credentialProblem(const SecurityFiles& f);

}  // namespace swa::dds
