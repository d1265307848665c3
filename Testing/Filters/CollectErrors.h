// SPDX-License-Identifier: BSD-3-Clause
// Collecting what VTK objects report (errors, warnings) in the filter tests.
#pragma once

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"

#include <string>

namespace volrad::test {

/// Appends the messages of the events it observes (vtkCommand::ErrorEvent,
/// WarningEvent) to `text`. Not copied or moved: the command points at it.
struct MessageCollector
{
  std::string text;
  vtkNew<vtkCallbackCommand> command;

  MessageCollector()
  {
    command->SetClientData(&text);
    command->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      *static_cast<std::string*>(self) += static_cast<const char*>(data);
    });
  }
  MessageCollector(const MessageCollector&) = delete;
  MessageCollector& operator=(const MessageCollector&) = delete;

  unsigned long observe(vtkObject* object, unsigned long event = vtkCommand::ErrorEvent)
  {
    return object->AddObserver(event, command);
  }
};

/// Updates the algorithm; returns the error messages it and its executive gave.
inline std::string updateCollectingErrors(vtkAlgorithm* f)
{
  MessageCollector errors;
  const unsigned long a = errors.observe(f);
  const unsigned long b = errors.observe(f->GetExecutive());
  f->Update();
  f->RemoveObserver(a);
  f->GetExecutive()->RemoveObserver(b);
  return errors.text;
}

} // namespace volrad::test
